// The two transports the gateway serves on: plain TCP (loopback, where the token never leaves
// the machine) and TLS (beyond it: HTTPS and WSS). Sessions are templates over these two.
#pragma once

#include <boost/beast/core.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <type_traits>

namespace flagsim::gateway {

using PlainStream = boost::beast::tcp_stream;
using TlsStream = boost::beast::ssl_stream<boost::beast::tcp_stream>;

template <class Stream>
constexpr bool kIsTls = std::is_same_v<Stream, TlsStream>;

}  // namespace flagsim::gateway
