//! A Markdown page as a self-contained HTML page (figures inlined, style inline, GitHub's
//! heading anchors): the reproduction report, a sweep's or a comparison's page.

use pulldown_cmark::{html, CowStr, Event, Options, Parser, Tag, TagEnd};
use std::collections::HashMap;
use std::path::Path;

/// GitHub's heading anchors: lower case, letters (with combining accents), digits, `-` and
/// `_` kept, spaces to `-`, the rest dropped; a repeated anchor gets `-1`, `-2`, ….
#[derive(Default)]
pub struct Anchors(HashMap<String, usize>);

impl Anchors {
    pub fn next(&mut self, heading: &str) -> String {
        let base: String = heading
            .trim()
            .to_lowercase()
            .chars()
            .filter_map(|c| match c {
                ' ' => Some('-'),
                // Letters with their combining marks (L̄), digits, `-`, `_`.
                c if c.is_alphanumeric()
                    || c == '-'
                    || c == '_'
                    || ('\u{300}'..='\u{36f}').contains(&c) =>
                {
                    Some(c)
                }
                _ => None,
            })
            .collect();
        let n = self.0.entry(base.clone()).or_insert(0);
        let id = if *n == 0 { base } else { format!("{base}-{n}") };
        *n += 1;
        id
    }
}

const STYLE: &str =
    "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1200px;\
margin:2em auto;padding:0 1em;line-height:1.45;color:#222}\
table{border-collapse:collapse;margin:1em 0;font-size:0.88em;display:block;overflow-x:auto;max-width:100%}\
th,td{border:1px solid #ccc;padding:0.25em 0.5em;text-align:left;vertical-align:top}\
th{background:#f2f2f2}tr:nth-child(even) td{background:#fafafa}\
img{max-width:100%;height:auto;border:1px solid #eee}\
code{background:#f5f5f5;padding:0 0.2em}\
blockquote{border-left:4px solid #c00;background:#fff4f4;margin:1em 0;padding:0.3em 1em}h1{font-size:1.6em}h2{border-bottom:1px solid #ddd}\
.fail{color:#b00000;background:#fde8e8;font-weight:bold;padding:0 0.25em;white-space:nowrap}\
.pass{color:#1a6b1a;font-weight:bold;white-space:nowrap}";

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        s.push(A[(n >> 18) as usize & 63] as char);
        s.push(A[(n >> 12) as usize & 63] as char);
        s.push(if chunk.len() > 1 {
            A[(n >> 6) as usize & 63] as char
        } else {
            '='
        });
        s.push(if chunk.len() > 2 {
            A[n as usize & 63] as char
        } else {
            '='
        });
    }
    s
}

/// A local image as a data URI (None if it cannot be read or is not PNG/SVG).
fn data_uri(base: &Path, url: &str) -> Option<String> {
    if url.contains("://") || url.starts_with("data:") {
        return None;
    }
    let mime = if url.ends_with(".png") {
        "image/png"
    } else if url.ends_with(".svg") {
        "image/svg+xml"
    } else {
        return None;
    };
    let bytes = std::fs::read(base.join(url)).ok()?;
    Some(format!("data:{mime};base64,{}", base64(&bytes)))
}

/// The Markdown as a self-contained HTML page: images under `base` are inlined; links to
/// local files are kept (they work when the page sits beside the output directories); every
/// heading gets its GitHub anchor as `id` (the table of contents links to them); a verdict is
/// coloured (red for ✗ does not hold, green for ✓ holds).
pub fn html(md: &str, base: &Path, title: &str) -> String {
    let mut events: Vec<Event> = Parser::new_ext(md, Options::ENABLE_TABLES)
        .map(|ev| match ev {
            Event::Start(Tag::Image {
                link_type,
                dest_url,
                title,
                id,
            }) => {
                let dest_url = data_uri(base, &dest_url).map_or(dest_url, CowStr::from);
                Event::Start(Tag::Image {
                    link_type,
                    dest_url,
                    title,
                    id,
                })
            }
            other => other,
        })
        .collect();
    let mut anchors = Anchors::default();
    let mut i = 0;
    while i < events.len() {
        if matches!(events[i], Event::Start(Tag::Heading { .. })) {
            let mut text = String::new();
            let mut j = i + 1;
            while j < events.len() && !matches!(events[j], Event::End(TagEnd::Heading(_))) {
                if let Event::Text(t) | Event::Code(t) = &events[j] {
                    text.push_str(t);
                }
                j += 1;
            }
            let anchor = anchors.next(&text);
            if let Event::Start(Tag::Heading { id, .. }) = &mut events[i] {
                *id = Some(CowStr::from(anchor));
            }
            i = j;
        }
        i += 1;
    }
    let mut body = String::new();
    html::push_html(&mut body, events.into_iter());
    let body = body
        .replace(
            "✗ <strong>does not hold</strong>",
            "<span class=\"fail\">✗ does not hold</span>",
        )
        .replace(
            "✓ <strong>holds</strong>",
            "<span class=\"pass\">✓ holds</span>",
        );
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        escape(title)
    )
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
