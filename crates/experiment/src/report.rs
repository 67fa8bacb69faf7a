//! The reproduction report over several experiments: `REPORT.md` and a self-contained
//! `report.html` (the same text; figures inlined as base64 data URIs, style inline).
//!
//! The homogeneous-road experiments get one numbered section each; the SR-99 experiments
//! share one section ("SR-99 corridor"), which ends with the `## SR-99 corridor` section of
//! the notes (the rest of the notes closes the report).

use crate::atomic::write_atomic;
use crate::experiments::{ExperimentName, ExperimentOutput, Figure};
use crate::safety;
use crate::table::md_table;
use crate::{Error, VERSION};
use pulldown_cmark::{html, CowStr, Event, Options, Parser, Tag};
use std::path::{Path, PathBuf};

/// What the report is made of.
pub struct ReportInput<'a> {
    pub outputs: &'a [ExperimentOutput],
    /// Markdown of the "Notes on differences" section.
    pub notes: &'a str,
    /// The command that produced it, e.g. `platoonsim reproduce --quick`.
    pub command: &'a str,
    /// Seeds per cell on the homogeneous road …
    pub seeds: u32,
    /// … and on SR-99 (if it was run).
    pub network_seeds: Option<u32>,
    /// Markdown at the start of the SR-99 section (e.g. what quick mode left out).
    pub network_note: &'a str,
    pub jobs: Option<usize>,
    pub wall_seconds: f64,
}

/// Push every Markdown heading one level down (`#` → `##`).
pub fn demote(md: &str) -> String {
    let mut s = String::with_capacity(md.len() + 64);
    for line in md.lines() {
        if line.starts_with('#') {
            s.push('#');
        }
        s.push_str(line);
        s.push('\n');
    }
    s
}

/// The notes as a section of the report: a level-2 heading first (added if missing; level-1
/// headings are pushed down).
pub fn notes_section(notes: &str) -> String {
    let t = notes.trim();
    if t.starts_with("# ") {
        demote(t)
    } else if t.starts_with('#') {
        format!("{t}\n")
    } else {
        format!("## Notes on differences\n\n{t}\n")
    }
}

/// The heading of the notes' SR-99 section.
pub const NETWORK_NOTES: &str = "## SR-99 corridor";

/// The notes without their `## SR-99 corridor` section, and that section's text (without its
/// heading; empty if there is none). The section runs to the next level-2 heading.
pub fn split_notes(notes: &str) -> (String, String) {
    let mut rest = String::new();
    let mut network = String::new();
    let mut inside = false;
    for line in notes.lines() {
        if line.starts_with("## ") || line.starts_with("# ") {
            inside = line.trim_end() == NETWORK_NOTES;
            if inside {
                continue;
            }
        }
        let out = if inside { &mut network } else { &mut rest };
        out.push_str(line);
        out.push('\n');
    }
    (rest, network.trim().to_string())
}

/// Whether an output belongs to the SR-99 section.
fn is_network(o: &ExperimentOutput) -> bool {
    ExperimentName::NETWORK.contains(&o.name)
}

/// `REPORT.md`.
pub fn markdown(input: &ReportInput<'_>) -> String {
    let computed: usize = input.outputs.iter().map(|o| o.computed).sum();
    let reused: usize = input.outputs.iter().map(|o| o.reused).sum();
    let mut md = String::from(
        "# platoonsim: reproduction of Woo & Skabardonis, \"Flow-Aware Platoon Formation of \
         CAVs in Mixed Traffic\"\n\n",
    );
    md.push_str(&format!(
        "Made by `{}` (platoonsim {VERSION}) with {} seeds per cell{} on {}. Total wall time \
         **{:.0} s** ({:.1} min): {computed} runs computed, {reused} reused from earlier run \
         files. Every number below is the mean over the seeds with the half-width of its 95 % \
         confidence interval (Student t); the paper reports single values without intervals. \
         Each experiment's files (every run, the statistics, provenance) are in its \
         directory beside this report.\n\n",
        input.command,
        input.seeds,
        match input.network_seeds {
            Some(n) if n != input.seeds => format!(" ({n} on SR-99)"),
            _ => String::new(),
        },
        match input.jobs {
            Some(n) => format!("{n} worker thread(s)"),
            None => format!(
                "{} worker thread(s)",
                std::thread::available_parallelism().map_or(1, |n| n.get())
            ),
        },
        input.wall_seconds,
        input.wall_seconds / 60.0
    ));

    md.push_str(&collisions_warning(input.outputs));
    md.push_str("## At a glance: the checks\n\n");
    for o in input.outputs {
        for c in &o.checks {
            md.push_str(&format!(
                "- {} — **{}**: {}\n",
                o.name.as_str(),
                if c.passed { "holds" } else { "does not hold" },
                c.statement
            ));
        }
    }
    md.push('\n');

    let (notes, network_notes) = split_notes(input.notes);
    let mut n = 0;
    let beyond = |o: &&ExperimentOutput| ExperimentName::BEYOND.contains(&o.name);
    for o in input
        .outputs
        .iter()
        .filter(|o| !is_network(o) && !beyond(o))
    {
        n += 1;
        md.push_str(&format!("## {n}. {}\n\n", o.name.title()));
        md.push_str(&section(o, 1));
    }
    let network: Vec<&ExperimentOutput> = input.outputs.iter().filter(|o| is_network(o)).collect();
    if !network.is_empty() {
        n += 1;
        md.push_str(&format!(
            "## {n}. SR-99 corridor (paper Table 4, Figs. 6-8)\n\n{}\n\n",
            input.network_note.trim()
        ));
        for o in network {
            md.push_str(&format!("### {}\n\n", o.name.title()));
            md.push_str(&section(o, 2));
        }
        if !network_notes.is_empty() {
            md.push_str("### Notes on the SR-99 results\n\n");
            md.push_str(&demote(&network_notes));
            md.push('\n');
        }
    }
    // Beyond the paper (issue 23's energy), after the paper's experiments.
    for o in input.outputs.iter().filter(beyond) {
        n += 1;
        md.push_str(&format!("## {n}. {}\n\n", o.name.title()));
        md.push_str(&section(o, 1));
    }

    md.push_str("## Run time\n\n");
    let header: Vec<String> = ["Experiment", "Runs", "Computed", "Reused", "Wall time (s)"]
        .iter()
        .map(|h| h.to_string())
        .collect();
    let mut rows: Vec<Vec<String>> = input
        .outputs
        .iter()
        .map(|o| {
            vec![
                o.name.as_str().to_string(),
                o.outcomes.len().to_string(),
                o.computed.to_string(),
                o.reused.to_string(),
                format!("{:.1}", o.wall_seconds),
            ]
        })
        .collect();
    rows.push(vec![
        "**total**".into(),
        input
            .outputs
            .iter()
            .map(|o| o.outcomes.len())
            .sum::<usize>()
            .to_string(),
        computed.to_string(),
        reused.to_string(),
        format!("{:.1}", input.wall_seconds),
    ]);
    md.push_str(&md_table(&header, &rows));
    md.push('\n');
    md.push_str(&notes_section(&notes));
    md
}

/// The warning at the top of the report when runs collided (empty if none): how many, and
/// every failed cell by experiment. A run with a collision is not physical traffic.
pub fn collisions_warning(outputs: &[ExperimentOutput]) -> String {
    let mut list = String::new();
    let mut n = 0;
    for o in outputs {
        let failed = safety::failed_cells(&o.cells, &o.outcomes);
        n += failed.iter().map(|f| f.seeds.len()).sum::<usize>();
        list.push_str(&safety::failed_list(
            &o.cells,
            &failed,
            &format!("{}: ", o.name.as_str()),
        ));
    }
    if n == 0 {
        return String::new();
    }
    let total: usize = outputs.iter().map(|o| o.outcomes.len()).sum();
    let mut md = format!(
        "> **Warning: {n} of {total} runs with collisions — these results are invalid.** In the \
         cells below, vehicles overlapped or ran past the end of a lane (a correct run has \
         none; docs/safety.md), and the cells' statistics include these runs. Each experiment's \
         Safety table marks them.\n>\n"
    );
    for l in list.lines() {
        md.push_str(&format!("> {l}\n"));
    }
    md.push('\n');
    md
}

/// An experiment's files, body and figures, its headings pushed `depth` levels down.
fn section(o: &ExperimentOutput, depth: usize) -> String {
    let mut md = format!(
        "Files: `{0}/summary.md`, `{0}/summary.csv`, `{0}/runs.csv`, `{0}/run.json`.\n\n",
        o.name.as_str()
    );
    let mut body = o.body.clone();
    for _ in 0..depth {
        body = demote(&body);
    }
    md.push_str(&body);
    if o.figures.is_empty() {
        md.push('\n');
    } else {
        md.push_str(&format!("\n{} Figures\n\n", "#".repeat(depth + 2)));
        md.push_str(&o.figures_md(&format!("{}/", o.name.as_str())));
    }
    md
}

const STYLE: &str =
    "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1200px;\
margin:2em auto;padding:0 1em;line-height:1.45;color:#222}\
table{border-collapse:collapse;margin:1em 0;font-size:0.88em}\
th,td{border:1px solid #ccc;padding:0.25em 0.5em;text-align:left;vertical-align:top}\
th{background:#f2f2f2}tr:nth-child(even) td{background:#fafafa}\
img{max-width:100%;height:auto;border:1px solid #eee}\
code{background:#f5f5f5;padding:0 0.2em}\
blockquote{border-left:4px solid #c00;background:#fff4f4;margin:1em 0;padding:0.3em 1em}h1{font-size:1.6em}h2{border-bottom:1px solid #ddd}";

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
/// local files are kept (they work when the page sits beside the output directories).
pub fn html(md: &str, base: &Path, title: &str) -> String {
    let parser = Parser::new_ext(md, Options::ENABLE_TABLES).map(|ev| match ev {
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
    });
    let mut body = String::new();
    html::push_html(&mut body, parser);
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

/// Write `REPORT.md` and `report.html` into `dir` (atomically); returns their paths.
pub fn write(dir: &Path, input: &ReportInput<'_>) -> Result<(PathBuf, PathBuf), Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let md = markdown(input);
    let page = html(&md, dir, "platoonsim reproduction report");
    let md_path = dir.join("REPORT.md");
    let html_path = dir.join("report.html");
    write_atomic(&md_path, md.as_bytes()).map_err(|e| Error::io(&md_path, e))?;
    write_atomic(&html_path, page.as_bytes()).map_err(|e| Error::io(&html_path, e))?;
    Ok((md_path, html_path))
}

/// The figure files of an output (PNG and SVG), for callers that copy or list them.
pub fn figure_files(o: &ExperimentOutput) -> Vec<PathBuf> {
    o.figures
        .iter()
        .flat_map(|Figure { stem, .. }| {
            ["png", "svg"].map(|ext| o.dir.join(format!("{stem}.{ext}")))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_reference_vectors() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
        assert_eq!(base64(&[0xff, 0xfe, 0x00]), "//4A");
    }

    #[test]
    fn html_inlines_local_images_and_renders_tables() {
        let dir = std::env::temp_dir().join(format!("platoonsim-report-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("capacity")).unwrap();
        std::fs::write(dir.join("capacity/fig.png"), b"\x89PNG fake").unwrap();
        let md = "# T\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n![cap](capacity/fig.png)\n\n![gone](missing.png)\n";
        let page = html(md, &dir, "x <y>");
        assert!(page.contains("<table>"));
        assert!(page.contains(&format!(
            "data:image/png;base64,{}",
            base64(b"\x89PNG fake")
        )));
        assert!(page.contains("src=\"missing.png\""));
        assert!(page.contains("<title>x &lt;y&gt;</title>"));
        assert!(!page.contains("capacity/fig.png"));
    }

    #[test]
    fn the_sr99_notes_are_split_off() {
        let notes = "## Notes on differences\n\nA.\n\n## SR-99 corridor\n\nB.\n\n### Sub\n\nC.\n\n## Later\n\nD.\n";
        let (rest, net) = split_notes(notes);
        assert_eq!(rest, "## Notes on differences\n\nA.\n\n## Later\n\nD.\n");
        assert_eq!(net, "B.\n\n### Sub\n\nC.");
        let (rest, net) = split_notes("plain");
        assert_eq!((rest.as_str(), net.as_str()), ("plain\n", ""));
    }

    #[test]
    fn headings_are_demoted_and_notes_get_a_heading() {
        assert_eq!(demote("# A\ntext\n## B"), "## A\ntext\n### B\n");
        assert_eq!(notes_section("plain"), "## Notes on differences\n\nplain\n");
        assert_eq!(
            notes_section("## Notes on differences\n\nx"),
            "## Notes on differences\n\nx\n"
        );
        assert!(notes_section("# Notes\n\n## Sub").starts_with("## Notes\n\n### Sub"));
    }
}
