#include "client/gateway/serve.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <unistd.h>

#include <boost/asio.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "client/gateway/gateway.hpp"
#include "client/gateway/http_session.hpp"
#include "client/gateway/server_context.hpp"
#include "client/gateway/tls_certificate.hpp"
#include "client/gateway/tls_detector.hpp"

namespace flagsim::gateway {
namespace {

namespace net = boost::asio;
using tcp = net::ip::tcp;

constexpr auto kTickInterval = std::chrono::milliseconds(20);  ///< command resends, status

/// PORT in decimal digits, 0 .. 65535; nullopt for anything else (a sign, a space, a letter, more).
std::optional<unsigned short> ParsePort(const std::string& text) {
  if (text.empty() || text.size() > 5) return std::nullopt;
  unsigned port = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    port = port * 10 + unsigned(c - '0');
  }
  if (port > 65535) return std::nullopt;
  return static_cast<unsigned short>(port);
}

}  // namespace

tcp::endpoint ParseListen(const std::string& listen) {
  const size_t colon = listen.rfind(':');
  if (colon == std::string::npos) throw std::invalid_argument("--listen " + listen + ": expected HOST:PORT");
  std::string host = listen.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  if (host == "localhost") host = "127.0.0.1";
  const std::string port_text = listen.substr(colon + 1);
  const std::optional<unsigned short> port = ParsePort(port_text);
  if (!port) {
    throw std::invalid_argument("--listen " + listen + ": the port '" + port_text +
                                "' is not one; allowed 0 .. 65535 in digits (0: any free port)");
  }
  boost::system::error_code error;
  const net::ip::address address = net::ip::make_address(host, error);
  if (error)
    throw std::invalid_argument("--listen " + listen + ": '" + host + "' is not an IP address or localhost");
  return {address, *port};
}

namespace {

/// The host parts of the URLs to print: the address listened on; for any address (0.0.0.0, ::),
/// this machine's own non-loopback IPv4 addresses (a host name may not resolve on the viewer's
/// machine), then 127.0.0.1 for this one.
std::vector<std::string> UrlHosts(const tcp::endpoint& endpoint) {
  const net::ip::address address = endpoint.address();
  if (!address.is_unspecified())
    return {address.is_v6() ? "[" + address.to_string() + "]" : address.to_string()};
  std::vector<std::string> hosts;
  ifaddrs* interfaces = nullptr;
  if (getifaddrs(&interfaces) == 0) {
    for (const ifaddrs* i = interfaces; i; i = i->ifa_next) {
      if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET || (i->ifa_flags & IFF_LOOPBACK)) continue;
      char text[INET_ADDRSTRLEN] = "";
      inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof(text));
      hosts.push_back(text);
    }
    freeifaddrs(interfaces);
  }
  hosts.push_back("127.0.0.1");
  return hosts;
}

class EventLoop {
 public:
  EventLoop(net::io_context& io, Bus& bus, ServerContext& context, const tcp::endpoint& endpoint)
      : io_(io),
        bus_(bus),
        context_(context),
        acceptor_(io, endpoint),
        bus_watch_(io, ::dup(bus.fileno())),
        ticker_(io),
        signals_(io, SIGINT, SIGTERM) {
    Accept();
    WatchBus();
    Tick();
    signals_.async_wait([this](const boost::system::error_code&, int) { io_.stop(); });
  }
  tcp::endpoint local_endpoint() const { return acceptor_.local_endpoint(); }

 private:
  void Accept() {
    acceptor_.async_accept([this](boost::system::error_code error, tcp::socket socket) {
      if (!error && context_.tls) std::make_shared<TlsDetector>(std::move(socket), context_)->Start();
      if (!error && !context_.tls)
        std::make_shared<HttpSession<PlainStream>>(PlainStream(std::move(socket)), context_)->Start();
      Accept();
    });
  }
  // The bus's descriptor is readable: dispatch everything waiting, then watch again.
  void WatchBus() {
    bus_watch_.async_wait(net::posix::stream_descriptor::wait_read, [this](boost::system::error_code error) {
      if (error) return;
      bus_.HandleAll();
      WatchBus();
    });
  }
  void Tick() {
    ticker_.expires_after(kTickInterval);
    ticker_.async_wait([this](boost::system::error_code error) {
      if (error) return;
      context_.gateway.Tick();
      Tick();
    });
  }

  net::io_context& io_;
  Bus& bus_;
  ServerContext& context_;
  tcp::acceptor acceptor_;
  net::posix::stream_descriptor bus_watch_;
  net::steady_timer ticker_;
  net::signal_set signals_;
};

/// The TLS the gateway serves with, if any: the user's pair; beyond loopback a self-signed one
/// for the addresses it serves (and this machine's name), unless plain HTTP was asked for.
/// Throws std::runtime_error (a file that cannot be read or written) or std::invalid_argument
/// (half a pair given).
std::optional<TlsSetup> TlsFor(const ServeOptions& options, const tcp::endpoint& endpoint) {
  if (options.tls_certificate.empty() != options.tls_key.empty())
    throw std::invalid_argument("give --tls-cert and --tls-key together");
  if (!options.tls_certificate.empty()) return LoadTls(options.tls_certificate, options.tls_key);
  if (endpoint.address().is_loopback() || options.plain_http) return std::nullopt;
  std::vector<std::string> hosts = UrlHosts(endpoint);
  char name[256] = "";
  if (gethostname(name, sizeof(name) - 1) == 0 && name[0] != '\0') hosts.push_back(name);
  return SelfSignedTls(options.tls_directory, hosts);
}

/// --servers => the selection; std::invalid_argument naming a prefix that is none.
ServerSelection SelectionOf(const std::vector<std::string>& servers, const Channels& channels) {
  if (servers.empty()) return ServerSelection::One(channels.prefix);
  if (servers.size() == 1 && servers[0] == "all") return ServerSelection::Many({});
  for (const std::string& prefix : servers) {
    const std::string problem = Channels::CheckPrefix(prefix);
    if (!problem.empty()) throw std::invalid_argument("--servers " + prefix + ": " + problem + ", or all");
  }
  return ServerSelection::Many(servers);
}

/// "ALPHA_, BETA_", "every server heard", or the one prefix.
std::string ServersText(const ServerSelection& selection) {
  if (selection.many && selection.prefixes.empty()) return "every server heard";
  std::string text;
  for (const std::string& prefix : selection.prefixes) text += (text.empty() ? "" : ", ") + prefix;
  return text;
}

}  // namespace

int Serve(Bus& bus, const Channels& channels, const ServeOptions& options) {
  tcp::endpoint endpoint;
  ServerSelection selection;
  try {
    endpoint = ParseListen(options.listen);
    selection = SelectionOf(options.servers, channels);
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "flagctl serve: %s\n", error.what());
    return 2;
  }
  std::optional<TlsSetup> tls;
  try {
    tls = TlsFor(options, endpoint);
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "flagctl serve: %s\n", error.what());
    return 2;
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "flagctl serve: %s\n", error.what());
    return 1;
  }
  GatewayOptions gateway_options;
  gateway_options.command_timeout = options.command_timeout;
  gateway_options.signer = options.signer;
  gateway_options.record_directory = options.record_directory;
  gateway_options.video_exporter = options.video_exporter;
  gateway_options.name = "flagsim (" + ServersText(selection) + " on " + bus.url() + ")";
  Gateway gateway(bus, selection, gateway_options);
  ServerContext context{gateway,
                        {options.token, endpoint.address().is_loopback(), options.allow_origins},
                        std::to_string(UnixMicros()),
                        0,
                        nullptr,
                        ""};
  if (context.access.token.empty() && !context.access.loopback) context.access.token = NewToken();
  if (tls) context.tls = tls->context.get();

  net::io_context io(1);
  std::unique_ptr<EventLoop> loop;
  try {
    loop = std::make_unique<EventLoop>(io, bus, context, endpoint);
  } catch (const boost::system::system_error& error) {
    std::fprintf(stderr, "flagctl serve: cannot listen on %s: %s\n", options.listen.c_str(), error.what());
    return 1;
  }
  const std::string query = context.access.token.empty() ? "" : "?token=" + context.access.token;
  const std::string secure = tls ? "s" : "";
  for (const std::string& name : UrlHosts(endpoint)) {
    const std::string host = name + ":" + std::to_string(loop->local_endpoint().port());
    if (context.https_hint.empty()) context.https_hint = "https://" + host + "/";
    std::printf("flagctl serve: live view   http%s://%s/%s\n", secure.c_str(), host.c_str(), query.c_str());
    std::printf("flagctl serve: Foxglove    ws%s://%s/%s  (Foxglove WebSocket connection)\n", secure.c_str(),
                host.c_str(), query.c_str());
  }
  if (tls) {
    std::printf("flagctl serve: TLS %s certificate %s, SHA-256 fingerprint %s%s\n",
                tls->self_signed ? "self-signed" : "", tls->certificate_path.c_str(),
                tls->fingerprint.c_str(),
                tls->self_signed ? " (check it against the browser's before trusting it)" : "");
  } else if (!endpoint.address().is_loopback()) {
    std::printf(
        "flagctl serve: warning: plain HTTP beyond loopback: the token crosses the network in clear\n");
  }
  std::printf("flagctl serve: bus %s, %s %s; recordings go to %s/\n", bus.url().c_str(),
              selection.many ? "servers" : "prefix", ServersText(selection).c_str(),
              options.record_directory.c_str());
  std::fflush(stdout);
  io.run();
  std::printf("flagctl serve: stopped\n");
  return 0;
}

}  // namespace flagsim::gateway
