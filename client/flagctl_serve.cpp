// flagctl serve: the live view's gateway (client/gateway/serve.hpp) on the bus of the globals.
#include <cstdio>
#include <memory>

#include "client/flagctl_commands.hpp"
#include "client/gateway/serve.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_key.hpp"

namespace flagsim {

namespace {

int Serve(const Globals& globals, const gateway::ServeOptions& options) {
  // A deep receive buffer: frames arrive as bursts of tiles (as for every flagctl reader).
  Bus bus(Bus::WithReceiveBuffer(globals.lcm_url, 8 << 20));
  const Channels channels(globals.prefix);
  gateway::ServeOptions serve = options;
  // Without --prefix or --servers: every server heard, each under its prefix.
  if (serve.servers.empty() && globals.prefix_option->count() == 0) serve.servers = {"all"};
  serve.command_timeout = globals.timeout;
  if (!globals.key_file.empty()) serve.signer = CommandSigner(ReadKeyFile(globals.key_file).front());
  serve.video_exporter = [globals](const std::string& log, const std::string& output,
                                   const std::atomic<bool>& stop) {
    return ExportLogTo(globals, log, output, stop);
  };
  return gateway::Serve(bus, channels, serve);
}

}  // namespace

void AddServeCommand(CLI::App& app, Invocation& invocation) {
  auto options = std::make_shared<gateway::ServeOptions>();
  gateway::ServeOptions& serve_options = *options;
  CLI::App* serve = app.add_subcommand(
      "serve",
      "serve the live view to browsers and Foxglove (the Foxglove WebSocket protocol) until interrupted");
  serve->add_option("--listen", serve_options.listen, "HOST:PORT to listen on (port 0: any free one)")
      ->capture_default_str();
  serve
      ->add_option(
          "--token", serve_options.token,
          "required on every request (?token=, a bearer header, or the page's cookie); generated when "
          "listening beyond loopback without one; from $FLAGSIM_TOKEN if set, which keeps it out of "
          "process listings")
      ->envname("FLAGSIM_TOKEN");
  serve->add_option(
      "--allow-origin", serve_options.allow_origins,
      "a browser origin allowed besides the gateway's own, e.g. https://app.foxglove.dev; * for any");
  serve
      ->add_option("--record-dir", serve_options.record_directory,
                   "where the page's recordings go, each with its MCAP and MP4 once stopped")
      ->capture_default_str();
  serve->add_option("--tls-cert", serve_options.tls_certificate,
                    "serve HTTPS and WSS with this certificate (PEM, with its chain); with --tls-key");
  serve->add_option("--tls-key", serve_options.tls_key, "the certificate's private key (PEM)");
  serve
      ->add_option(
          "--tls-dir", serve_options.tls_directory,
          "beyond loopback without --tls-cert: where the self-signed certificate is kept (made once)")
      ->capture_default_str();
  serve->add_flag(
      "--plain-http", serve_options.plain_http,
      "beyond loopback, serve plain HTTP (behind a proxy that adds TLS): the token crosses in clear");
  serve
      ->add_option(
          "--servers", serve_options.servers,
          "serve several servers, each under /PREFIX (/ALPHA_/flag/tiles): these prefixes, or all for "
          "every server heard on the bus; without it, the one server of --prefix with plain topics")
      ->delimiter(',');
  serve->footer(
      "Commands from browsers go out as WIND, PARAM, CAMERA, KEYFRAME and REFRESH and are answered with\n"
      "the server's ACK; --timeout is how long the gateway waits for one. The protocol, channels and\n"
      "services are in docs/live-view.md.");

  invocation.RunOnParse(serve, [&invocation, options] { return Serve(invocation.globals, *options); });
}

}  // namespace flagsim
