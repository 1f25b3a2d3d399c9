#include "client/gateway/refusal_page.hpp"

namespace flagsim::gateway {
namespace {

std::string Escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

/// What to do about it, by status.
std::string Hint(int status) {
  if (status == 401) {
    return "<p>This live view needs its token. <code>flagctl serve</code> printed the address to "
           "open when it started, ending in <code>?token=&hellip;</code>: open that one (the "
           "token is then kept in a cookie for this page). Started with <code>scripts/live.sh</code>, "
           "it is in that script's output; a token given to it (<code>--token</code> or "
           "<code>$FLAGSIM_TOKEN</code>) is the one to add. Ask whoever runs the server if you have "
           "neither.</p>"
           "<form method=\"get\" action=\"/\"><label>Token <input name=\"token\" autocomplete=\"off\" "
           "spellcheck=\"false\" size=\"34\" required autofocus></label> <button>Open the live view</button></form>";
  }
  if (status == 403) {
    return "<p>This gateway serves only its own machine (loopback) unless it was started with a "
           "token: open it as <code>http://127.0.0.1:PORT/</code> there, or start it with "
           "<code>--listen 0.0.0.0:PORT</code>, which makes a token and prints the address to share.</p>";
  }
  return "";
}

}  // namespace

bool WantsHtml(std::string_view accept) { return accept.find("text/html") != std::string_view::npos; }

std::string RefusalHtml(int status, const std::string& reason) {
  const std::string title = status == 401 ? "A token is needed" : status == 403 ? "Not allowed here" : "Refused";
  return "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" "
         "content=\"width=device-width, initial-scale=1\"><title>flagsim live view: " + title +
         "</title><style>body{font:15px/1.5 system-ui,sans-serif;max-width:40em;margin:3em auto;padding:0 1em;"
         "color:#ddd;background:#15181d}code{background:#262b33;padding:0 .3em;border-radius:3px}"
         "h1{font-size:1.3em}input,button{font:inherit;padding:.2em .5em}</style></head><body><h1>flagsim live view: " + title + "</h1><p>" +
         std::to_string(status) + ": " + Escaped(reason) + "</p>" + Hint(status) + "</body></html>\n";
}

}  // namespace flagsim::gateway
