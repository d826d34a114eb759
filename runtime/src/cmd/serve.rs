//! `sdfc serve`: a folder's files (the playground by default) over HTTP on this machine.

use crate::cli::ServeArgs;
use std::path::{Path, PathBuf};

/// Runs `sdfc serve` until it is stopped; returns the exit code (1: the folder or the address
/// cannot be had).
pub fn run(args: &ServeArgs) -> i32 {
    let dir = args
        .dir
        .clone()
        .unwrap_or_else(|| PathBuf::from("target/web"));
    if !dir.join("index.html").is_file() {
        say!(
            "error: `{}` has no index.html: build the playground first (`bash scripts/build_web.sh` \
             in sdfc's repository assembles it in target/web), or name a folder to serve",
            dir.display()
        );
        return 1;
    }
    // tiny_http: a small, synchronous server (one request at a time is plenty for one page).
    let server = match tiny_http::Server::http((args.host, args.port)) {
        Ok(s) => s,
        Err(e) => {
            say!("error: cannot listen on {}:{}: {e}", args.host, args.port);
            return 1;
        }
    };
    let address = server
        .server_addr()
        .to_ip()
        .map_or("?".into(), |a| a.to_string());
    // Always said (also with --quiet): without the address the command is of no use.
    say!(
        "serving {} at http://{address}/ (Ctrl-C stops)",
        dir.display()
    );
    for request in server.incoming_requests() {
        let response = respond(&dir, request.method(), request.url());
        let _ = request.respond(response);
    }
    0
}

/// The answer to `method` `url`: the file under `root` (`/` is `index.html`), 404 where there
/// is none, 405 for anything but GET and HEAD. Paths leaving the folder (`..`) or naming hidden
/// files are not served.
fn respond(
    root: &Path,
    method: &tiny_http::Method,
    url: &str,
) -> tiny_http::Response<std::io::Cursor<Vec<u8>>> {
    use tiny_http::{Method, Response};
    if !matches!(method, Method::Get | Method::Head) {
        return Response::from_string("only GET and HEAD\n").with_status_code(405);
    }
    let path = url.split(['?', '#']).next().unwrap_or("");
    let mut file = root.to_path_buf();
    for part in path.split('/').filter(|p| !p.is_empty()) {
        if part.starts_with('.') || part.contains('\\') || part.contains('%') {
            return Response::from_string("not found\n").with_status_code(404);
        }
        file.push(part);
    }
    if file.is_dir() {
        file.push("index.html");
    }
    match std::fs::read(&file) {
        Ok(bytes) => {
            let kind = content_type(&file);
            let header = tiny_http::Header::from_bytes(&b"Content-Type"[..], kind.as_bytes());
            let response = Response::from_data(bytes);
            match header {
                Ok(h) => response.with_header(h),
                Err(()) => response,
            }
        }
        Err(_) => Response::from_string("not found\n").with_status_code(404),
    }
}

/// The media type a browser needs for the playground's kinds of files (WebAssembly's and
/// modules' own matter: a page refuses a module served as text).
fn content_type(file: &Path) -> &'static str {
    match file.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "html" => "text/html; charset=utf-8",
        "js" | "mjs" => "text/javascript; charset=utf-8",
        "wasm" => "application/wasm",
        "json" => "application/json",
        "css" => "text/css; charset=utf-8",
        "png" => "image/png",
        "svg" => "image/svg+xml",
        "wgsl" | "frag" | "glsl" | "sdf" | "txt" | "md" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serves_files_and_nothing_outside_the_folder() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("index.html"), "<p>hi</p>").unwrap();
        std::fs::write(dir.path().join(".secret"), "no").unwrap();
        let get = tiny_http::Method::Get;
        let status = |url: &str| respond(dir.path(), &get, url).status_code().0;
        assert_eq!(status("/"), 200);
        assert_eq!(status("/index.html?x=1#s=abc"), 200);
        assert_eq!(status("/missing.js"), 404);
        assert_eq!(status("/../Cargo.toml"), 404);
        assert_eq!(status("/%2e%2e/Cargo.toml"), 404);
        assert_eq!(status("/.secret"), 404);
        assert_eq!(
            respond(dir.path(), &tiny_http::Method::Post, "/")
                .status_code()
                .0,
            405
        );
        assert_eq!(content_type(Path::new("a/sdfc.wasm")), "application/wasm");
    }
}
