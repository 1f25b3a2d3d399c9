#include "client/gateway/websocket_session.hpp"

#include <array>
#include <chrono>
#include <cstdio>

namespace flagsim::gateway {
namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace http = beast::http;

constexpr const char* kSubprotocol = "foxglove.websocket.v1";

std::chrono::milliseconds Milliseconds(double seconds) {
  return std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000));
}

}  // namespace

template <class Stream>
WebSocketSession<Stream>::WebSocketSession(Stream stream, ServerContext& context, std::string address)
    : socket_(std::move(stream)),
      context_(context),
      address_(std::move(address)),
      write_deadline_(socket_.get_executor()) {
  ++context_.websocket_clients;
}

template <class Stream>
WebSocketSession<Stream>::~WebSocketSession() { --context_.websocket_clients; }

template <class Stream>
void WebSocketSession<Stream>::Accept(http::request<http::string_body> request) {
  beast::get_lowest_layer(socket_).expires_never();  // the WebSocket's own timeouts from here on
  websocket::stream_base::timeout timeouts{};
  timeouts.handshake_timeout = Milliseconds(ServerContext::kHandshakeTimeout);
  timeouts.idle_timeout = Milliseconds(3 * ServerContext::kWriteTimeout);  // pings keep a live client open
  timeouts.keep_alive_pings = true;
  socket_.set_option(timeouts);
  socket_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
    response.set(http::field::sec_websocket_protocol, kSubprotocol);
    response.set(http::field::server, "flagctl serve");
  }));
  socket_.read_message_max(ServerContext::kMaxClientMessageBytes);
  socket_.auto_fragment(false);
  socket_.async_accept(request, beast::bind_front_handler(&WebSocketSession<Stream>::OnAccept, this->shared_from_this()));
}

template <class Stream>
void WebSocketSession<Stream>::OnAccept(beast::error_code error) {
  if (error) return;
  open_ = true;
  id_ = context_.gateway.Attach(this);
  protocol_.emplace(context_.gateway, id_);
  protocol_->Start(context_.gateway.options().name, context_.session_id);
  Read();
  Write();
}

template <class Stream>
void WebSocketSession<Stream>::Read() {
  socket_.async_read(read_buffer_, beast::bind_front_handler(&WebSocketSession<Stream>::OnRead, this->shared_from_this()));
}

// A message too large (read_message_max), a broken frame or a closed socket ends the session.
template <class Stream>
void WebSocketSession<Stream>::OnRead(beast::error_code error, size_t) {
  if (error) return Drop(nullptr);
  const std::string message = beast::buffers_to_string(read_buffer_.data());
  read_buffer_.consume(read_buffer_.size());
  if (socket_.got_text()) {
    protocol_->OnText(message);
  } else {
    protocol_->OnBinary(message);
  }
  if (protocol_->overflowed()) return Drop("its queue overflowed");
  Write();
  Read();
}

template <class Stream>
void WebSocketSession<Stream>::Write() {
  if (!open_ || write_in_flight_) return;
  if (protocol_->overflowed()) return Drop("its queue overflowed");
  std::optional<Outgoing> next = protocol_->Next();
  if (!next) return;
  writing_ = std::move(*next);
  write_in_flight_ = true;
  socket_.binary(writing_.binary);
  const std::array<boost::asio::const_buffer, 2> buffers = {
      boost::asio::buffer(writing_.head),
      writing_.body ? boost::asio::buffer(*writing_.body) : boost::asio::const_buffer()};
  write_deadline_.expires_after(Milliseconds(ServerContext::kWriteTimeout));
  write_deadline_.async_wait([weak = this->weak_from_this()](beast::error_code error) {
    if (auto self = weak.lock(); self && !error) self->Drop("it stopped reading");
  });
  socket_.async_write(buffers, beast::bind_front_handler(&WebSocketSession<Stream>::OnWrite, this->shared_from_this()));
}

template <class Stream>
void WebSocketSession<Stream>::OnWrite(beast::error_code error, size_t) {
  write_in_flight_ = false;
  write_deadline_.cancel();
  writing_ = Outgoing{};
  if (error) return Drop(nullptr);
  Write();
}

// Closing the socket ends the pending read and write with errors, which release the session.
template <class Stream>
void WebSocketSession<Stream>::Drop(const char* why) {
  if (!open_) return;
  open_ = false;
  context_.gateway.Detach(id_);
  if (why != nullptr) {
    ++context_.gateway.counters().clients_dropped;
    std::fprintf(stderr, "flagctl serve: dropped client %d (%s): %s\n", id_, address_.c_str(), why);
  }
  beast::error_code ignored;
  beast::get_lowest_layer(socket_).socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
  beast::get_lowest_layer(socket_).close();
  write_deadline_.cancel();
}

template class WebSocketSession<PlainStream>;
template class WebSocketSession<TlsStream>;

}  // namespace flagsim::gateway
