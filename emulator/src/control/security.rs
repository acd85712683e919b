//! Who may drive the machine through the control port (issue 15 item 6).
//!
//! - A token, when one is required (configured, or generated because the port is bound to an
//!   address other than 127.0.0.1 or ::1): every API request carries `Authorization: Bearer <token>` (or
//!   `?token=` on `GET /api/v1/stream`, which a browser's `EventSource` opens without headers);
//!   without it, 401.
//! - Cross-site requests: a request whose `Origin` is not this server (a web page elsewhere
//!   posting to it from the user's browser) is refused with 403, except for plain reads (`GET`
//!   of JSON, which the browser will not show the other page). The stream counts as a
//!   state-carrying upgrade and is checked too. Bodies must be JSON already (`JsonBody`), so a
//!   form post is refused even without an `Origin`.

use std::hash::{BuildHasher, Hasher};
use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;

use axum::extract::{Request, State};
use axum::http::{header, HeaderMap, Method};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;

/// The API's access rule.
#[derive(Clone, Debug, Default)]
pub struct Access {
    token: Option<Arc<str>>,
}

impl Access {
    /// No token needed (a loopback bind without a configured token).
    pub fn open() -> Access {
        Access::default()
    }

    /// The rule for a port bound to `bind` with the configured `token`: a configured token is
    /// always required; without one a bind to 127.0.0.1 or ::1 is open and any other address
    /// gets a generated token. Returns the rule and the token to print when one was generated.
    pub fn for_bind(bind: SocketAddr, token: Option<&str>) -> (Access, Option<String>) {
        match token {
            Some(t) => (
                Access {
                    token: Some(Arc::from(t)),
                },
                None,
            ),
            // Only the usual loopback addresses: 127.0.0.2 stands for "another address" in the
            // tests (issue 15), and a port bound there was bound there on purpose.
            None if is_default_loopback(bind.ip()) => (Access::open(), None),
            None => {
                let t = generate_token();
                (
                    Access {
                        token: Some(Arc::from(t.as_str())),
                    },
                    Some(t),
                )
            }
        }
    }

    pub fn requires_token(&self) -> bool {
        self.token.is_some()
    }

    fn admits(&self, request: &Request) -> bool {
        let Some(expected) = &self.token else {
            return true;
        };
        let from_header = request
            .headers()
            .get(header::AUTHORIZATION)
            .and_then(|v| v.to_str().ok())
            .and_then(|v| v.strip_prefix("Bearer "));
        let from_query = request
            .uri()
            .query()
            .and_then(|q| q.split('&').find_map(|pair| pair.strip_prefix("token=")));
        from_header
            .into_iter()
            .chain(from_query)
            .any(|given| same(given.as_bytes(), expected.as_bytes()))
    }
}

/// 127.0.0.1 or ::1.
fn is_default_loopback(ip: IpAddr) -> bool {
    ip == IpAddr::from([127, 0, 0, 1]) || ip == IpAddr::from(std::net::Ipv6Addr::LOCALHOST)
}

/// Compares in time independent of where the strings differ.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

/// 128 random bits as 32 hex digits, from the standard library's per-process random hash keys
/// (no extra crate for a one-off secret).
pub fn generate_token() -> String {
    let mut token = String::with_capacity(32);
    for i in 0..2u64 {
        let mut h = std::collections::hash_map::RandomState::new().build_hasher();
        h.write_u64(i);
        h.write_u128(
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos()),
        );
        token.push_str(&format!("{:016x}", h.finish()));
    }
    token
}

/// The `Origin` header when it names another server than `Host`.
fn foreign_origin(headers: &HeaderMap) -> Option<(String, String)> {
    let origin = headers.get(header::ORIGIN)?.to_str().unwrap_or("?");
    let host = headers
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .unwrap_or("");
    // `null` (sandboxed frames, file: pages) is foreign too.
    let origin_host = origin
        .strip_prefix("http://")
        .or_else(|| origin.strip_prefix("https://"))
        .unwrap_or("");
    (origin_host.is_empty() || !origin_host.eq_ignore_ascii_case(host))
        .then(|| (origin.to_string(), host.to_string()))
}

/// The middleware in front of every API route.
pub async fn guard(State(access): State<Access>, request: Request, next: Next) -> Response {
    if !access.admits(&request) {
        return ApiError::Unauthorized.into_response();
    }
    let checked = request.method() != Method::GET && request.method() != Method::HEAD
        || request.uri().path() == "/api/v1/stream";
    if checked {
        if let Some((origin, host)) = foreign_origin(request.headers()) {
            return ApiError::CrossOrigin { origin, host }.into_response();
        }
    }
    next.run(request).await
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;
    use axum::http::HeaderValue;

    #[test]
    fn loopback_is_open_other_addresses_get_a_token() {
        let (a, printed) = Access::for_bind("127.0.0.1:8700".parse().unwrap(), None);
        assert!(!a.requires_token() && printed.is_none());
        let (a, printed) = Access::for_bind("127.0.0.2:8700".parse().unwrap(), None);
        assert!(a.requires_token());
        assert_eq!(printed.unwrap().len(), 32);
        let (a, printed) = Access::for_bind("[::1]:8700".parse().unwrap(), None);
        assert!(!a.requires_token() && printed.is_none());
        let (a, printed) = Access::for_bind("127.0.0.1:8700".parse().unwrap(), Some("t"));
        assert!(a.requires_token() && printed.is_none());
        assert_ne!(generate_token(), generate_token());
    }

    #[test]
    fn tokens_come_in_the_header_or_the_query() {
        let (access, _) = Access::for_bind("0.0.0.0:1".parse().unwrap(), Some("secret"));
        let req = |uri: &str, auth: Option<&str>| {
            let mut r = Request::builder().uri(uri);
            if let Some(a) = auth {
                r = r.header(header::AUTHORIZATION, a);
            }
            r.body(axum::body::Body::empty()).unwrap()
        };
        assert!(access.admits(&req("/api/v1/state", Some("Bearer secret"))));
        assert!(access.admits(&req("/api/v1/stream?axes=0&token=secret", None)));
        assert!(!access.admits(&req("/api/v1/state", None)));
        assert!(!access.admits(&req("/api/v1/state", Some("Bearer secreT"))));
        assert!(!access.admits(&req("/api/v1/state?token=secre", None)));
    }

    #[test]
    fn origins_other_than_the_host_are_foreign() {
        let headers = |origin: Option<&'static str>| {
            let mut h = HeaderMap::new();
            h.insert(header::HOST, HeaderValue::from_static("127.0.0.1:8700"));
            if let Some(o) = origin {
                h.insert(header::ORIGIN, HeaderValue::from_static(o));
            }
            h
        };
        assert!(foreign_origin(&headers(None)).is_none());
        assert!(foreign_origin(&headers(Some("http://127.0.0.1:8700"))).is_none());
        assert!(foreign_origin(&headers(Some("http://evil.example"))).is_some());
        assert!(foreign_origin(&headers(Some("http://127.0.0.1:8701"))).is_some());
        assert!(foreign_origin(&headers(Some("null"))).is_some());
    }
}
