// What a refused request reads. A browser (Accept: text/html) gets a page that says what was
// wrong and where to look: for a missing or wrong token, that `flagctl serve` printed the URL
// with it (?token=...), and how to ask for it again; other clients get the reason as plain text.
#pragma once

#include <string>
#include <string_view>

namespace flagsim::gateway {

/// Whether an Accept header asks for HTML (a browser navigating to the page).
bool WantsHtml(std::string_view accept);

/// The HTML page for refusal `status` (401, 403, ...) with `reason`, escaped.
std::string RefusalHtml(int status, const std::string& reason);

}  // namespace flagsim::gateway
