//! Which web pages may use the server, and what every answer tells the browser about the page.
//!
//! Without a token (the default, allowed on loopback only) anything that reaches the port may
//! use the API, and a web page open in the user's browser reaches it too:
//!
//! - A DNS-rebinding page (a name of the attacker's that resolves to its own server, then to
//!   127.0.0.1) is, to the browser, of the same origin as the server: it reads every answer.
//!   Its requests carry its own name in `Host`, so a request whose `Host` is none of the
//!   server's names ([`Guard`]) gets 421.
//! - A page of another origin cannot read the answers (the server sends no CORS headers
//!   unless told to), but it can send a request that changes something (a form's POST, a
//!   `fetch` in `no-cors` mode); the browser names the page in `Origin`. So a POST, PUT,
//!   PATCH or DELETE whose `Origin` is neither the server's own nor a `--cors-origin` gets
//!   403. Without `Origin` (curl, the Python client) the request is served, unless the
//!   browser's `Sec-Fetch-Site` says it comes from another site.
//!
//! With a token neither check applies: a browser attaches no `Authorization` header by
//! itself, so neither page can make an API call, and the routes without a token only read.
//! Checking `Host` then would only break proxies that forward another name.
//!
//! Every answer, whatever made it, carries [`security_headers`]: the page's content policy
//! (scripts and styles from the server's own files only, no framing) unless the handler set
//! its own ([`REPORT_POLICY`]), `nosniff`, no framing, no referrer.

use std::net::{IpAddr, Ipv6Addr, SocketAddr};
use std::sync::Arc;

use axum::extract::{Request, State};
use axum::http::{HeaderMap, HeaderName, HeaderValue, Method, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;
use super::extract::cut;

/// The page's content policy, on every answer but a report's. Scripts and styles only from
/// the server's files (the page has no inline script, style element or style attribute; the
/// modules set styles through the DOM, which a policy does not restrict); images also as
/// `data:` URLs (the page's icon, the contact map drawn to a PNG, a figure's export); no
/// plugins, no `<base>`, forms only to the server, and no page may frame it, so its buttons
/// cannot be clicked through a transparent frame.
pub(crate) const PAGE_POLICY: &str = "default-src 'self'; script-src 'self'; \
     style-src 'self'; img-src 'self' data:; connect-src 'self'; object-src 'none'; \
     base-uri 'none'; form-action 'self'; frame-ancestors 'none'";

/// A report's content policy: a report is one self-contained HTML file whose styles are an
/// inline `<style>` element and attributes, and it runs no script and loads nothing. So
/// nothing is loaded, only inline styles apply, and `sandbox` gives it an origin of its
/// own, should it ever hold a script.
pub(crate) const REPORT_POLICY: &str = "default-src 'none'; style-src 'unsafe-inline'; \
     img-src data:; base-uri 'none'; form-action 'none'; frame-ancestors 'none'; sandbox";

/// A name the server answers to, in `Host` or in an `Origin`: lower case, an IPv6 address in
/// brackets in its shortest form, and the port (`None`: any port, or none was given).
#[derive(Debug, Clone, PartialEq, Eq)]
struct HostName {
    name: String,
    port: Option<u16>,
}

impl HostName {
    /// `NAME[:PORT]` as `Host` carries it: a DNS name, an IPv4 address, or an IPv6 address
    /// in brackets; `None` for anything else (a scheme, a path, a bare IPv6 address).
    fn parse(text: &str) -> Option<Self> {
        let text = text.trim().to_ascii_lowercase();
        let (name, port) = if let Some(rest) = text.strip_prefix('[') {
            let (address, after) = rest.split_once(']')?;
            let address: Ipv6Addr = address.parse().ok()?;
            (format!("[{address}]"), after)
        } else {
            let end = text.find(':').unwrap_or(text.len());
            let name = &text[..end];
            let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | '_');
            if name.is_empty() || !name.chars().all(allowed) {
                return None;
            }
            (name.to_owned(), &text[end..])
        };
        let port = match after_colon(port)? {
            None => None,
            Some(digits) if digits.bytes().all(|b| b.is_ascii_digit()) => {
                Some(digits.parse().ok()?)
            }
            Some(_) => return None,
        };
        Some(Self { name, port })
    }

    /// Whether a request naming `asked` is for this name: the same name, and the same port
    /// unless this one takes any. A name without a port is on its scheme's default port,
    /// which a proxy in front may make either 80 or 443.
    fn admits(&self, asked: &Self) -> bool {
        self.name == asked.name
            && match (self.port, asked.port) {
                (None, _) => true,
                (Some(mine), Some(asked)) => mine == asked,
                (Some(mine), None) => mine == 80 || mine == 443,
            }
    }
}

/// What follows a name: nothing (`Some(None)`), or `:PORT` (`Some(Some(PORT))`); `None` for
/// anything else.
fn after_colon(rest: &str) -> Option<Option<&str>> {
    match rest.strip_prefix(':') {
        None if rest.is_empty() => Some(None),
        None => None,
        Some("") => None,
        Some(port) => Some(Some(port)),
    }
}

/// The names and origins a server without a token serves; see the module's comment.
#[derive(Debug)]
pub(crate) struct Guard {
    /// The names requests may carry in `Host`; `None` when the server has a token, and
    /// nothing is checked.
    hosts: Option<Vec<HostName>>,
    /// The `--cors-origin` values, which may also change things.
    cors_origins: Vec<String>,
}

impl Guard {
    /// The guard of a server listening on `addr`: with `token`, one that checks nothing;
    /// otherwise its own names (`localhost`, `127.0.0.1`, `[::1]` and the address it listens
    /// on, each on its port) and the `--allowed-host` values; refuses the first value that
    /// is not a host name.
    pub(crate) fn new(
        addr: SocketAddr,
        token: bool,
        allowed_hosts: &[String],
        cors_origins: &[String],
    ) -> Result<Self, NotAHostName> {
        let mut hosts = own_names(addr);
        for allowed in allowed_hosts {
            hosts.push(HostName::parse(allowed).ok_or_else(|| NotAHostName(allowed.clone()))?);
        }
        Ok(Self {
            hosts: (!token).then_some(hosts),
            cors_origins: cors_origins.to_vec(),
        })
    }

    /// Refuses a request under a name the server does not answer to (421), and one that
    /// changes something and comes from a page of another origin (403).
    fn check(&self, method: &Method, headers: &HeaderMap) -> Result<(), ApiError> {
        let Some(hosts) = &self.hosts else {
            return Ok(());
        };
        let admitted = |asked: &HostName| hosts.iter().any(|host| host.admits(asked));
        let host = headers.get(header::HOST).and_then(|v| v.to_str().ok());
        if !host.and_then(HostName::parse).is_some_and(|h| admitted(&h)) {
            return Err(misdirected(host.unwrap_or_default(), &hosts[0]));
        }
        if method.is_safe() {
            return Ok(());
        }
        match headers
            .get(header::ORIGIN)
            .map(|v| v.to_str().unwrap_or(""))
        {
            Some(origin) if self.cors_origins.iter().any(|o| o == origin) => Ok(()),
            Some(origin) if origin_host(origin).is_some_and(|h| admitted(&h)) => Ok(()),
            Some(origin) => Err(foreign(&format!("a page of {:?}", cut(origin)))),
            // No `Origin`: not a browser, unless a browser says it comes from elsewhere.
            None => match headers.get(SEC_FETCH_SITE).map(HeaderValue::as_bytes) {
                Some(b"cross-site" | b"same-site") => Err(foreign("a page of another site")),
                _ => Ok(()),
            },
        }
    }
}

/// An `--allowed-host` value that is not a host name (with an optional port): the value.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct NotAHostName(pub(crate) String);

/// `Sec-Fetch-Site`: where a browser's request comes from, relative to the server.
const SEC_FETCH_SITE: &str = "sec-fetch-site";

/// The names of the server itself on `addr`'s port: the loopback names, and the address it
/// listens on when that is another.
fn own_names(addr: SocketAddr) -> Vec<HostName> {
    let port = Some(addr.port());
    let listening = match addr.ip() {
        IpAddr::V4(ip) => ip.to_string(),
        IpAddr::V6(ip) => format!("[{ip}]"),
    };
    let mut names = vec![listening];
    for name in ["127.0.0.1", "localhost", "[::1]"] {
        if !names.iter().any(|n| n == name) {
            names.push(name.to_owned());
        }
    }
    names
        .into_iter()
        .map(|name| HostName { name, port })
        .collect()
}

/// The host of an `Origin` (`http://NAME[:PORT]` or `https://...`), its port made explicit
/// from the scheme; `None` for another scheme or `null` (a sandboxed frame, a file).
fn origin_host(origin: &str) -> Option<HostName> {
    let (scheme, authority) = origin.split_once("://")?;
    let default_port = match scheme.to_ascii_lowercase().as_str() {
        "http" => 80,
        "https" => 443,
        _ => return None,
    };
    let mut host = HostName::parse(authority)?;
    host.port = host.port.or(Some(default_port));
    Some(host)
}

/// 421 for a `Host` the server does not answer to, naming the flag that adds one.
fn misdirected(host: &str, own: &HostName) -> ApiError {
    let port = own.port.map(|p| format!(":{p}")).unwrap_or_default();
    ApiError::misdirected(format!(
        "this server answers to {}{port} (or localhost{port}), not to the host {:?}: a server \
         without a token serves only its own address, so that a page of another site \
         cannot reach it under a name of its own (DNS rebinding). Behind a reverse proxy \
         with another name, start it with --allowed-host NAME, or set a token",
        own.name,
        cut(host)
    ))
}

/// 403 for a request that would change something, sent by `whom` (another origin's page).
fn foreign(whom: &str) -> ApiError {
    ApiError::forbidden(format!(
        "{whom} may not change anything here: a server without a token takes requests that \
         change something only from its own page. Allow that origin with --cors-origin, or \
         name the server's host with --allowed-host, or set a token"
    ))
}

/// The middleware of [`Guard::check`], before anything else reads the request.
pub(crate) async fn guard(
    State(guard): State<Arc<Guard>>,
    request: Request,
    next: Next,
) -> Response {
    match guard.check(request.method(), request.headers()) {
        Ok(()) => next.run(request).await,
        Err(refusal) => refusal.into_response(),
    }
}

/// Gives every answer the security headers (errors, files and event streams included): the
/// page's content policy where the handler set none, `X-Content-Type-Options: nosniff` (a
/// JSON answer is never run as a script or shown as a page), `X-Frame-Options: DENY` (the
/// policy's `frame-ancestors` for browsers that predate it), `Referrer-Policy: no-referrer`
/// (job ids in the address stay on the server) and `Cross-Origin-Resource-Policy:
/// same-origin` (another site's page cannot embed an answer, as an image or a script).
pub(crate) async fn security_headers(request: Request, next: Next) -> Response {
    let mut response = next.run(request).await;
    let headers = response.headers_mut();
    if !headers.contains_key(header::CONTENT_SECURITY_POLICY) {
        headers.insert(
            header::CONTENT_SECURITY_POLICY,
            HeaderValue::from_static(PAGE_POLICY),
        );
    }
    let fixed = [
        (header::X_CONTENT_TYPE_OPTIONS, "nosniff"),
        (header::X_FRAME_OPTIONS, "DENY"),
        (header::REFERRER_POLICY, "no-referrer"),
        (
            HeaderName::from_static("cross-origin-resource-policy"),
            "same-origin",
        ),
    ];
    for (name, value) in fixed {
        headers.insert(name, HeaderValue::from_static(value));
    }
    response
}

#[cfg(test)]
mod tests {
    use super::*;

    fn host(text: &str) -> Option<HostName> {
        HostName::parse(text)
    }

    fn guard(token: bool, allowed: &[&str]) -> Guard {
        let allowed: Vec<String> = allowed.iter().map(|&a| a.to_owned()).collect();
        let cors = vec!["http://localhost:3000".to_owned()];
        Guard::new(
            "127.0.0.1:8080".parse().expect("addr"),
            token,
            &allowed,
            &cors,
        )
        .expect("guard")
    }

    fn status(guard: &Guard, method: &Method, pairs: &[(&str, &str)]) -> u16 {
        let mut headers = HeaderMap::new();
        for &(name, value) in pairs {
            let name = HeaderName::from_bytes(name.as_bytes()).expect("name");
            headers.insert(name, HeaderValue::from_str(value).expect("value"));
        }
        guard
            .check(method, &headers)
            .map_or_else(|e| e.status().as_u16(), |()| 200)
    }

    #[test]
    fn host_names_are_parsed_as_host_carries_them() {
        let localhost = HostName {
            name: "localhost".into(),
            port: Some(8080),
        };
        assert_eq!(host("LocalHost:8080"), Some(localhost));
        assert_eq!(host("[0:0::1]:80").map(|h| h.name), Some("[::1]".into()));
        assert_eq!(host("lab.example").map(|h| h.port), Some(None));
        for bad in [
            "", ":80", "::1", "a b", "http://x", "x/y", "x:", "x:+1", "x:65536", "[::1",
        ] {
            assert_eq!(host(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn only_the_server_s_names_and_the_allowed_hosts_are_served() {
        let guard = guard(false, &["lab.example", "proxy.example:8443"]);
        let get = |h: &str| status(&guard, &Method::GET, &[("host", h)]);
        for good in [
            "127.0.0.1:8080",
            "localhost:8080",
            "[::1]:8080",
            "lab.example",
            "lab.example:1",
        ] {
            assert_eq!(get(good), 200, "{good}");
        }
        assert_eq!(get("proxy.example:8443"), 200);
        for bad in [
            "127.0.0.1:8081",
            "localhost",
            "rebind.example:8080",
            "proxy.example:1",
        ] {
            assert_eq!(get(bad), 421, "{bad}");
        }
        assert_eq!(status(&guard, &Method::GET, &[]), 421, "no Host");
    }

    #[test]
    fn only_the_server_s_own_pages_and_cors_origins_change_things() {
        let guard = guard(false, &["lab.example"]);
        let post = |pairs: &[(&str, &str)]| {
            let mut all = vec![("host", "127.0.0.1:8080")];
            all.extend_from_slice(pairs);
            status(&guard, &Method::POST, &all)
        };
        assert_eq!(post(&[]), 200, "no Origin: not a browser");
        for own in [
            "http://127.0.0.1:8080",
            "http://localhost:8080",
            "https://lab.example",
        ] {
            assert_eq!(post(&[("origin", own)]), 200, "{own}");
        }
        assert_eq!(
            post(&[("origin", "http://localhost:3000")]),
            200,
            "a --cors-origin"
        );
        for other in [
            "http://127.0.0.1:3001",
            "null",
            "http://evil.example:8080",
            "file://",
        ] {
            assert_eq!(post(&[("origin", other)]), 403, "{other}");
        }
        assert_eq!(post(&[("sec-fetch-site", "cross-site")]), 403);
        assert_eq!(post(&[("sec-fetch-site", "same-origin")]), 200);
        let from_other = [
            ("host", "127.0.0.1:8080"),
            ("origin", "http://evil.example"),
        ];
        assert_eq!(
            status(&guard, &Method::GET, &from_other),
            200,
            "reads are not refused"
        );
        assert_eq!(status(&guard, &Method::DELETE, &from_other), 403);
    }

    #[test]
    fn a_token_turns_the_checks_off_and_a_bad_allowed_host_is_an_error() {
        let guard = guard(true, &[]);
        let pairs = [
            ("host", "rebind.example"),
            ("origin", "http://evil.example"),
        ];
        assert_eq!(status(&guard, &Method::POST, &pairs), 200);
        let addr = "127.0.0.1:8080".parse().expect("addr");
        let error = Guard::new(addr, false, &["http://lab.example/".to_owned()], &[]);
        let refused = NotAHostName("http://lab.example/".to_owned());
        assert_eq!(error.err(), Some(refused));
    }
}
