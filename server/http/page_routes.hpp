#pragma once
/// @file The routes of the web page (docs/web.md): the page, its files and the example scenes it offers.

#include "server/http/httplib.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

/// The web page (docs/web.md); it asks for the token itself when the API answers 401.
void get_page(App&, const httplib::Request&, httplib::Response& res);

/// A file of the page (its script and style, Debian's dygraphs), as compiled in.
void get_asset(App&, const httplib::Request& req, httplib::Response& res);

/// The example scenes of api/examples (compiled in) that the service can run: name, title, scene.
void list_examples(App&, const httplib::Request&, httplib::Response& res);

}  // namespace stoss::server::http
