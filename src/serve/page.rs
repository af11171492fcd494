//! What `serve` adds to a page: the live-reload script and, while the last build failed, the
//! error at the top. Nothing else of the page changes.

/// Where an open page listens for "rebuilt": server-sent events, one per build.
pub const EVENTS_PATH: &str = "/__mechbook/events";

/// The script a served page carries: it reloads the page when a build has finished since the
/// page was made (`generation`), even one that finished before the script connected.
pub fn reload_snippet(generation: u64) -> String {
    format!(
        "<script>/* mechbook serve: live reload */(()=>{{const s=new EventSource(\"{EVENTS_PATH}?since={generation}\");s.onmessage=()=>{{s.close();location.reload();}};}})();</script>"
    )
}

/// What went wrong in the last build, in a box fixed at the top of the page: why it wrote
/// nothing, or (`written`) the checks that failed in the site it wrote.
pub fn error_box(messages: &[String], written: bool) -> String {
    let heading = if written {
        "mechbook: the site was built, but these checks failed (run `mechbook check` for the whole report). Fix the scene and save: the page reloads."
    } else {
        "mechbook: the last build failed; this is the last good site. Fix the scene and save: the page reloads."
    };
    let mut html = format!(
        "<div id=\"mechbook-serve-error\" role=\"alert\" style=\"position:fixed;top:0;left:0;right:0;z-index:2147483647;max-height:60vh;overflow:auto;margin:0;padding:1em 1.5em;background:#fff4f4;color:#5c0000;border-bottom:3px solid #b00020;font:14px/1.45 ui-monospace,monospace;white-space:pre-wrap\"><strong>{heading}</strong>\n",
    );
    for m in messages {
        html.push('\n');
        html.push_str(&tera::escape_html(m));
    }
    html.push_str("</div>");
    html
}

/// A note at the foot of the page while its build's PDFs are being typeset: the page itself
/// is up to date, and reloads again when they are ready.
pub fn pdfs_pending_note(count: usize) -> String {
    let what = if count == 1 {
        "1 PDF is".to_owned()
    } else {
        format!("{count} PDFs are")
    };
    format!(
        "<div id=\"mechbook-serve-pdfs\" role=\"status\" style=\"position:fixed;bottom:0;right:0;z-index:2147483647;margin:0;padding:.4em 1em;background:#f4f8ff;color:#12325a;border:1px solid #8aa8d0;font:13px/1.4 system-ui,sans-serif\">mechbook: this page is up to date; {what} being typeset, and the page reloads when they are ready.</div>"
    )
}

/// The page served for a PDF that a build is still typesetting: it shows the PDF when it is
/// ready.
pub fn pdf_pending_page(url_path: &str, generation: u64) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>mechbook: typesetting</title></head><body><p>mechbook is typesetting {}; this page shows it when it is ready.</p>{}</body></html>\n",
        tera::escape_html(url_path),
        reload_snippet(generation)
    )
}

/// `page` with `extra` inserted before its last `</body>` (or at its end).
pub fn inject(page: &[u8], extra: &str) -> Vec<u8> {
    let at = page
        .windows(7)
        .rposition(|w| w.eq_ignore_ascii_case(b"</body>"))
        .unwrap_or(page.len());
    let mut out = Vec::with_capacity(page.len() + extra.len());
    out.extend_from_slice(&page[..at]);
    out.extend_from_slice(extra.as_bytes());
    out.extend_from_slice(&page[at..]);
    out
}

/// A page of its own for when no build has written a site yet: the first build is running
/// (no messages), or it failed.
pub fn no_site_page(messages: &[String], generation: u64) -> String {
    let (title, body) = if messages.is_empty() {
        (
            "mechbook: building",
            "<p>mechbook is building the site; this page reloads when it is done.</p>".to_owned(),
        )
    } else {
        ("mechbook: build failed", error_box(messages, false))
    };
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{title}</title></head><body>{body}{}</body></html>\n",
        reload_snippet(generation)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_snippet_goes_before_the_last_body_end_and_nothing_else_changes() {
        let page = b"<html><body><p>a</p></body></html>\n";
        let out = inject(page, "<x>");
        assert_eq!(out, b"<html><body><p>a</p><x></body></html>\n");
        // Removing what was inserted gives the page back, byte for byte.
        let text = String::from_utf8(out).unwrap();
        assert_eq!(text.replacen("<x>", "", 1).as_bytes(), page);
        assert_eq!(inject(b"plain", "<x>"), b"plain<x>");
    }

    #[test]
    fn the_error_is_escaped() {
        let b = error_box(&["a.toml:1:2: unexpected `<`".into()], false);
        assert!(b.contains("a.toml:1:2: unexpected `&lt;`"), "{b}");
        assert!(!b.contains("`<`"));
    }
}
