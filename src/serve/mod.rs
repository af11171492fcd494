//! The HTTP side of `mechbook serve`: the built site's files as they are on disk, each HTML
//! page with the live-reload script (and, while the last build failed, its error), and a
//! stream of server-sent events that tells open pages to reload after each build. Reads
//! files only; `site` writes them. axum on a single-threaded tokio runtime in its own thread.

pub mod page;

use axum::body::Body;
use axum::extract::State;
use axum::http::{HeaderMap, HeaderValue, StatusCode, Uri, header};
use axum::response::sse::{Event, Sse};
use axum::response::{IntoResponse, Response};
use std::convert::Infallible;
use std::net::SocketAddr;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, Mutex};
use tokio::sync::watch;

#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    #[error(
        "cannot listen on 127.0.0.1:{port}: {source}; choose another --port, or leave it out for \
         a free one"
    )]
    Bind {
        port: u16,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot start the HTTP server: {0}")]
    Runtime(#[source] std::io::Error),
}

/// What the pages are told: the count of builds so far (each one reloads open pages), and what
/// went wrong in the last one: why it wrote nothing, or the checks that failed in the site it
/// wrote.
#[derive(Debug, Clone, Default)]
struct Status {
    generation: u64,
    written: bool,
    problems: Vec<String>,
    /// The site's PDFs a build after this one is typesetting (paths inside the site).
    pdfs_pending: Vec<String>,
}

struct Shared {
    root: PathBuf,
    /// The port served: only requests for 127.0.0.1 or localhost at it are answered.
    port: u16,
    status: Mutex<Status>,
    /// The generation, or `None` to end every open event stream at shutdown.
    changes: watch::Sender<Option<u64>>,
}

/// A running server. Dropping it does not stop it: call [`Server::stop`].
pub struct Server {
    shared: Arc<Shared>,
    addr: SocketAddr,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Server {
    /// Binds 127.0.0.1:`port` (0 for a free port) and serves the folder `root` from a thread of
    /// its own. `on_interrupt` runs once when the process gets Ctrl-C (SIGINT) or SIGTERM.
    pub fn start(
        root: &Path,
        port: u16,
        on_interrupt: impl FnOnce() + Send + 'static,
    ) -> Result<Server, ServeError> {
        let listener = std::net::TcpListener::bind(("127.0.0.1", port))
            .map_err(|source| ServeError::Bind { port, source })?;
        let addr = listener
            .local_addr()
            .map_err(|source| ServeError::Bind { port, source })?;
        listener
            .set_nonblocking(true)
            .map_err(|source| ServeError::Bind { port, source })?;
        let (changes, _) = watch::channel(Some(0));
        let shared = Arc::new(Shared {
            root: root.to_path_buf(),
            port: addr.port(),
            status: Mutex::new(Status::default()),
            changes,
        });
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(ServeError::Runtime)?;
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let app = axum::Router::new()
            .route(page::EVENTS_PATH, axum::routing::get(events))
            .fallback(axum::routing::get(file))
            .with_state(shared.clone());
        let for_shutdown = shared.clone();
        let thread = std::thread::Builder::new()
            .name("mechbook-serve".into())
            .spawn(move || {
                runtime.block_on(async move {
                    let listener = match tokio::net::TcpListener::from_std(listener) {
                        Ok(l) => l,
                        Err(e) => {
                            eprintln!("mechbook: error: cannot serve: {e}");
                            return;
                        }
                    };
                    let shutdown = async move {
                        tokio::select! {
                            _ = stopped => {}
                            _ = interrupted() => on_interrupt(),
                        }
                        // Ends the open event streams, so that the server can finish.
                        for_shutdown.changes.send_replace(None);
                    };
                    if let Err(e) = axum::serve(listener, app)
                        .with_graceful_shutdown(shutdown)
                        .await
                    {
                        eprintln!("mechbook: error: the HTTP server stopped: {e}");
                    }
                });
            })
            .map_err(ServeError::Runtime)?;
        Ok(Server {
            shared,
            addr,
            stop: Some(stop),
            thread: Some(thread),
        })
    }

    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// A build has finished: whether it wrote the site, what went wrong (why it did not, or
    /// the checks that failed), and the PDFs left out of it for the next build to typeset.
    /// Open pages reload.
    pub fn built(&self, written: bool, problems: Vec<String>, pdfs_pending: Vec<String>) {
        let generation = {
            let mut s = self.shared.status.lock().unwrap_or_else(|p| p.into_inner());
            s.generation += 1;
            s.written = written;
            s.problems = problems;
            s.pdfs_pending = pdfs_pending;
            s.generation
        };
        self.shared.changes.send_replace(Some(generation));
    }

    /// How many pages are listening for reloads now.
    pub fn listeners(&self) -> usize {
        self.shared.changes.receiver_count()
    }

    /// Stops serving: open event streams end, and the server's thread is joined.
    pub fn stop(mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// Ctrl-C, or SIGTERM from a service manager or a test.
async fn interrupted() {
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    tokio::select! {
        _ = tokio::signal::ctrl_c() => {}
        _ = term => {}
    }
}

/// One "reload" event for each build after the page's own (`?since=N`), until shutdown.
async fn events(State(shared): State<Arc<Shared>>, headers: HeaderMap, uri: Uri) -> Response {
    if !is_loopback_host(&headers, shared.port) {
        return misdirected(shared.port);
    }
    let rx = shared.changes.subscribe();
    let since = uri
        .query()
        .and_then(|q| q.split('&').find_map(|kv| kv.strip_prefix("since=")))
        .and_then(|n| n.parse::<u64>().ok())
        .unwrap_or(0);
    let stream = futures_util::stream::unfold((rx, since), |(mut rx, seen)| async move {
        loop {
            let current = *rx.borrow_and_update();
            match current {
                None => return None,
                Some(g) if g > seen => {
                    let event: Result<Event, Infallible> = Ok(Event::default().data("reload"));
                    return Some((event, (rx, g)));
                }
                Some(_) => {}
            }
            if rx.changed().await.is_err() {
                return None;
            }
        }
    });
    let mut response = Sse::new(stream).into_response();
    response
        .headers_mut()
        .insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    response
}

/// A file of the site; an HTML page gets the reload script and, after a failed build, the
/// error. No file outside the site is ever read.
async fn file(State(shared): State<Arc<Shared>>, headers: HeaderMap, uri: Uri) -> Response {
    if !is_loopback_host(&headers, shared.port) {
        return misdirected(shared.port);
    }
    let status = shared
        .status
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .clone();
    let Some(rel) = site_path(uri.path()) else {
        return plain(StatusCode::BAD_REQUEST, "bad path");
    };
    // Site files are small and local: a blocking read is shorter than the request itself.
    let read = if is_hidden(&rel) {
        Err(std::io::ErrorKind::NotFound.into())
    } else {
        read_inside(&shared.root, &rel)
    };
    let bytes = match read {
        Ok(b) => b,
        Err(_) if !shared.root.join("index.html").exists() => {
            return html(
                StatusCode::SERVICE_UNAVAILABLE,
                page::no_site_page(&status.problems, status.generation).into_bytes(),
            );
        }
        Err(_) if is_pending(&status.pdfs_pending, &rel) => {
            return html(
                StatusCode::SERVICE_UNAVAILABLE,
                page::pdf_pending_page(uri.path(), status.generation).into_bytes(),
            );
        }
        Err(_) => {
            return plain(
                StatusCode::NOT_FOUND,
                &format!("{} is not part of the site", uri.path()),
            );
        }
    };
    let kind = content_type(&rel);
    if kind.starts_with("text/html") {
        let mut extra = String::new();
        if !status.problems.is_empty() {
            extra.push_str(&page::error_box(&status.problems, status.written));
        }
        if !status.pdfs_pending.is_empty() {
            extra.push_str(&page::pdfs_pending_note(status.pdfs_pending.len()));
        }
        extra.push_str(&page::reload_snippet(status.generation));
        return html(StatusCode::OK, page::inject(&bytes, &extra));
    }
    respond(StatusCode::OK, kind, bytes)
}

/// Whether `rel` is one of the PDFs being typeset.
fn is_pending(pending: &[String], rel: &Path) -> bool {
    pending.iter().any(|p| Path::new(p) == rel)
}

/// A file of the site by its path inside it, never through a link that leads out of it.
fn read_inside(root: &Path, rel: &Path) -> std::io::Result<Vec<u8>> {
    let root = std::fs::canonicalize(root)?;
    let path = std::fs::canonicalize(root.join(rel))?;
    if !path.starts_with(&root) {
        return Err(std::io::ErrorKind::NotFound.into());
    }
    std::fs::read(path)
}

/// Whether the request names this server: 127.0.0.1 or localhost, at its port or none. Any
/// other name is refused, so that a web page elsewhere cannot read the site through a name
/// it controls (DNS rebinding).
fn is_loopback_host(headers: &HeaderMap, port: u16) -> bool {
    let Some(host) = headers.get(header::HOST).and_then(|h| h.to_str().ok()) else {
        return false;
    };
    let (name, at) = match host.rsplit_once(':') {
        Some((name, p)) => (name, p.parse::<u16>().ok()),
        None => (host, Some(port)),
    };
    at == Some(port) && (name == "127.0.0.1" || name.eq_ignore_ascii_case("localhost"))
}

fn misdirected(port: u16) -> Response {
    plain(
        StatusCode::MISDIRECTED_REQUEST,
        &format!(
            "mechbook serve answers only http://127.0.0.1:{port}/ and http://localhost:{port}/"
        ),
    )
}

/// Whether a relative path passes through a hidden name: the build's own files (the site's
/// marker, the cache, staging folders, temporary files) and editors' swap files.
pub fn is_hidden(rel: &Path) -> bool {
    rel.components()
        .any(|c| c.as_os_str().to_string_lossy().starts_with('.'))
}

/// The file a URL path names inside the site: `/` and `dir/` are their `index.html`; `..`, a
/// root or a drive is refused.
fn site_path(url_path: &str) -> Option<PathBuf> {
    let decoded = percent_decode(url_path)?;
    let mut rel = PathBuf::new();
    for c in Path::new(decoded.trim_start_matches('/')).components() {
        match c {
            Component::Normal(n) => rel.push(n),
            Component::CurDir => {}
            _ => return None,
        }
    }
    if decoded.ends_with('/') || rel.as_os_str().is_empty() {
        rel.push("index.html");
    }
    Some(rel)
}

fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("svg") => "image/svg+xml",
        Some("xml") => "application/xml",
        Some("json") => "application/json",
        Some("js") => "text/javascript; charset=utf-8",
        Some("png") => "image/png",
        Some("pdf") => "application/pdf",
        Some("txt") | Some("md") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

fn respond(status: StatusCode, kind: &'static str, bytes: Vec<u8>) -> Response {
    let mut r = Response::new(Body::from(bytes));
    *r.status_mut() = status;
    let h = r.headers_mut();
    h.insert(header::CONTENT_TYPE, HeaderValue::from_static(kind));
    // Every request sees the newest build.
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    r
}

fn html(status: StatusCode, bytes: Vec<u8>) -> Response {
    respond(status, "text/html; charset=utf-8", bytes)
}

fn plain(status: StatusCode, text: &str) -> Response {
    respond(
        status,
        "text/plain; charset=utf-8",
        text.as_bytes().to_vec(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn url_paths_stay_inside_the_site() {
        assert_eq!(site_path("/"), Some(PathBuf::from("index.html")));
        assert_eq!(site_path("/hoop.html"), Some(PathBuf::from("hoop.html")));
        assert_eq!(
            site_path("/handouts/"),
            Some(PathBuf::from("handouts/index.html"))
        );
        assert_eq!(site_path("/a%20b.html"), Some(PathBuf::from("a b.html")));
        assert_eq!(site_path("/../etc/passwd"), None);
        assert_eq!(site_path("/plots/%2e%2e/%2e%2e/x"), None);
        assert_eq!(site_path("/%zz"), None);
    }

    #[test]
    fn only_the_loopback_names_at_the_port_are_answered() {
        let with = |host: &str| {
            let mut h = HeaderMap::new();
            h.insert(header::HOST, HeaderValue::from_str(host).unwrap());
            is_loopback_host(&h, 8000)
        };
        for ok in [
            "127.0.0.1:8000",
            "localhost:8000",
            "LocalHost:8000",
            "127.0.0.1",
        ] {
            assert!(with(ok), "{ok}");
        }
        for refused in [
            "evil.example:8000",
            "127.0.0.1:8001",
            "localhost.evil.example:8000",
            "127.0.0.1.nip.io:8000",
            "",
        ] {
            assert!(!with(refused), "{refused}");
        }
        assert!(!is_loopback_host(&HeaderMap::new(), 8000), "no Host at all");
    }
}
