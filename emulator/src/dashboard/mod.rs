//! The dashboard (issue 15): plain HTML, CSS and JavaScript modules served at `/` of the
//! control listener, embedded in the binary so `mcemu run` serves them with no build step and
//! no network. The page reads `GET /api/v1/state`, streams `GET /api/v1/stream` and sends the
//! control API's own requests; it has no API of its own. uPlot (MIT) is vendored under
//! `web/vendor/uplot/` by `scripts/vendor-web`.

use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;

/// One embedded file: its URL path, content type and bytes.
struct Asset {
    path: &'static str,
    content_type: &'static str,
    body: &'static str,
}

const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";
const HTML: &str = "text/html; charset=utf-8";

/// An [`Asset`] of `web/FILE` served at `PATH`.
macro_rules! asset {
    ($path:literal, $content_type:expr, $file:literal) => {
        Asset {
            path: $path,
            content_type: $content_type,
            body: include_str!(concat!("web/", $file)),
        }
    };
}

/// Every file the page loads.
const ASSETS: [Asset; 10] = [
    asset!("/", HTML, "index.html"),
    asset!("/dashboard/style.css", CSS, "style.css"),
    asset!("/dashboard/app.js", JS, "app.js"),
    asset!("/dashboard/api.js", JS, "api.js"),
    asset!("/dashboard/machine.js", JS, "machine.js"),
    asset!("/dashboard/scope.js", JS, "scope.js"),
    asset!("/dashboard/csv.js", JS, "csv.js"),
    asset!("/dashboard/decimate.js", JS, "decimate.js"),
    asset!(
        "/dashboard/vendor/uplot/uPlot.esm.js",
        JS,
        "vendor/uplot/uPlot.esm.js"
    ),
    asset!(
        "/dashboard/vendor/uplot/uPlot.min.css",
        CSS,
        "vendor/uplot/uPlot.min.css"
    ),
];

/// The page's routes (no state, no token: the files hold nothing secret).
pub fn routes<S: Clone + Send + Sync + 'static>() -> Router<S> {
    let router = ASSETS.iter().fold(Router::new(), |router, asset| {
        let (content_type, body) = (asset.content_type, asset.body);
        router.route(
            asset.path,
            get(move || async move { serve(content_type, body) }),
        )
    });
    // Browsers ask for it unbidden; no icon, and no 404 in the page's console.
    router.route("/favicon.ico", get(|| async { StatusCode::NO_CONTENT }))
}

fn serve(content_type: &'static str, body: &'static str) -> Response {
    let mut response = body.into_response();
    let headers = response.headers_mut();
    headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(content_type));
    // The page may not be framed by another site (clickjacking the controls).
    headers.insert(header::X_FRAME_OPTIONS, HeaderValue::from_static("DENY"));
    headers.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(
            "default-src 'self'; style-src 'self' 'unsafe-inline'; frame-ancestors 'none'",
        ),
    );
    response
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_page_writes_the_trace_csv_columns_of_trace_rs() {
        let csv = ASSETS
            .iter()
            .find(|a| a.path == "/dashboard/csv.js")
            .map(|a| a.body)
            .unwrap_or_default();
        let list = csv
            .split("export const HEADER = [")
            .nth(1)
            .and_then(|rest| rest.split("];").next())
            .unwrap_or_default();
        let columns: Vec<&str> = list
            .split(',')
            .map(|c| c.trim().trim_matches('"'))
            .filter(|c| !c.is_empty())
            .collect();
        assert_eq!(columns.join(","), crate::trace::HEADER);
    }

    #[test]
    fn every_module_the_page_imports_is_served() {
        for asset in &ASSETS {
            for line in asset.body.lines() {
                let Some(from) = line.split(" from \"./").nth(1) else {
                    continue;
                };
                let Some(name) = from.split('"').next() else {
                    continue;
                };
                let dir = asset.path.rsplit_once('/').map_or("", |(d, _)| d);
                let wanted = format!("{dir}/{name}");
                assert!(
                    ASSETS.iter().any(|a| a.path == wanted),
                    "{} imports {wanted}, which is not served",
                    asset.path
                );
            }
        }
    }
}
