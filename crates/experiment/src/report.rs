//! The reproduction report over several experiments: `REPORT.md` and a self-contained
//! `report.html` (the same text; figures inlined as base64 data URIs, style inline).
//!
//! It holds this run's results only: a header (date, version, commit, seeds, host, wall time),
//! a table of contents, the checks at a glance (✓ holds / ✗ does not hold), then one numbered
//! section per homogeneous-road experiment and one for the SR-99 experiments, each with our
//! numbers beside the paper's and the difference. The project's reproduction notes (where the
//! reproduction stands, why the figures differ from the paper's, with the measurements of
//! earlier runs) stay in `docs/` and are linked, never copied: their figures come from other
//! runs.

use crate::experiments::{ExperimentOutput, Figure, Part};
use crate::table::md_table;
use platoonsim_runs::atomic::write_atomic;
pub use platoonsim_runs::page::{base64, html, Anchors};
use platoonsim_runs::safety;
use platoonsim_runs::{Error, VERSION};
use platoonsim_scenario::Preset;
use std::path::{Path, PathBuf};

/// Where and when the report was made (the header's provenance).
#[derive(Clone, Debug, Default)]
pub struct Provenance {
    /// UTC date and time, e.g. `2026-12-02 07:10 UTC`.
    pub date: String,
    /// `git describe` of the source tree, or "unknown".
    pub commit: String,
    /// Host name, operating system, architecture and core count.
    pub host: String,
}

/// What the report is made of.
pub struct ReportInput<'a> {
    pub outputs: &'a [ExperimentOutput],
    pub provenance: Provenance,
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

/// The reproduction notes of the homogeneous road and of SR-99 (paths in the repository).
pub const NOTEBOOK: &str = "docs/reproduction-notes.md";
pub const NOTEBOOK_SR99: &str = "docs/reproduction-notes-sr99.md";

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

/// Whether an output belongs to the SR-99 section.
fn is_network(o: &ExperimentOutput) -> bool {
    o.name.part == Part::Network
}

/// A check's verdict, visible at a glance: a symbol and the words (the HTML page colours it).
pub fn verdict(passed: bool) -> &'static str {
    if passed {
        "✓ **holds**"
    } else {
        "✗ **does not hold**"
    }
}

/// The experiments' own check lists say `**holds**` / `**does not hold**`; the report puts
/// the symbol in front.
fn mark_verdicts(md: &str) -> String {
    md.replace("**does not hold**", "✗ **does not hold**")
        .replace("- **holds**", "- ✓ **holds**")
}

/// The text a reader sees in a Markdown heading (code spans and emphasis markers removed).
fn heading_text(line: &str) -> String {
    line.trim_start_matches('#').trim().replace(['`', '*'], "")
}

/// A table of contents of the level-2 and level-3 headings of `md` (after the title), linked
/// to their anchors; `md` is the whole document so that repeated headings are numbered as a
/// renderer numbers them.
pub fn contents(md: &str) -> String {
    let mut anchors = Anchors::default();
    let mut toc = String::new();
    let mut fenced = false;
    for line in md.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        }
        if fenced || !line.starts_with('#') {
            continue;
        }
        let text = heading_text(line);
        let id = anchors.next(&text);
        let level = line.chars().take_while(|&c| c == '#').count();
        if (2..=3).contains(&level) && text != "Contents" {
            let indent = if level == 3 { "  " } else { "" };
            toc.push_str(&format!("{indent}- [{text}](#{id})\n"));
        }
    }
    toc
}

/// Civil date and time (UTC) of a Unix time, `YYYY-MM-DD HH:MM UTC`.
pub fn utc(unix_s: u64) -> String {
    let days = (unix_s / 86_400) as i64;
    let secs = unix_s % 86_400;
    // Days since 1970-01-01 to a civil date (the proleptic Gregorian calendar).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1_460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02} UTC",
        secs / 3_600,
        secs % 3_600 / 60
    )
}

/// `REPORT.md`.
pub fn markdown(input: &ReportInput<'_>) -> String {
    let computed: usize = input.outputs.iter().map(|o| o.computed).sum();
    let reused: usize = input.outputs.iter().map(|o| o.reused).sum();
    let p = &input.provenance;
    let threads = input
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let seeds = match input.network_seeds {
        Some(n) if n != input.seeds => format!(
            "{} per cell on the homogeneous road, {n} per cell on SR-99",
            input.seeds
        ),
        _ => format!("{} per cell", input.seeds),
    };
    let mut head = String::from(
        "# platoonsim reproduction report: Woo & Skabardonis, \"Flow-Aware Platoon Formation \
         of CAVs in Mixed Traffic\"\n\n",
    );
    let rows = vec![
        vec!["Date".to_string(), p.date.clone()],
        vec![
            "Version".into(),
            format!("platoonsim {VERSION}, commit `{}`", p.commit),
        ],
        vec!["Command".into(), format!("`{}`", input.command)],
        vec!["Seeds".into(), seeds],
        vec![
            "Host".into(),
            format!("{}; {threads} worker thread(s)", p.host),
        ],
        vec![
            "Wall time".into(),
            format!(
                "{:.0} s ({:.1} min): {computed} runs computed, {reused} reused from earlier run \
                 files",
                input.wall_seconds,
                input.wall_seconds / 60.0
            ),
        ],
    ];
    head.push_str(&md_table(&["Run".to_string(), "".to_string()], &rows));
    head.push_str(&format!(
        "\nEvery number is this run's: the mean over the seeds with the half-width of its 95 % \
         confidence interval (Student t), beside the paper's value (single values without \
         intervals) and the difference. A check reads ✓ **holds** or ✗ **does not hold**. Why \
         our figures differ from the paper's, with the measurements behind each explanation, is \
         in the project's reproduction notes, `{NOTEBOOK}` (homogeneous road) and \
         `{NOTEBOOK_SR99}` (SR-99 corridor), by topic; their figures come from earlier runs and \
         are not repeated here. Each experiment's files (every run, the statistics, \
         provenance) are in its directory beside this report.\n\n"
    ));

    let mut md = collisions_warning(input.outputs);
    md.push_str("## At a glance: the checks\n\n");
    let mut glance = Vec::new();
    for o in input.outputs {
        for c in &o.checks {
            glance.push(vec![
                verdict(c.passed).to_string(),
                rel_dir(o),
                c.statement.clone(),
            ]);
        }
    }
    md.push_str(&md_table(
        &["Result".into(), "Experiment".into(), "Check".into()],
        &glance,
    ));
    md.push('\n');

    // The paper's model first (issue 43), then the engine's rules over it, then the
    // platform's defaults; within each, the homogeneous road, SR-99, beyond the paper.
    let paper = |o: &&ExperimentOutput| o.settings.preset == Preset::Paper;
    let rules = |o: &&ExperimentOutput| o.name.part == Part::Rules;
    let mut n = 0;
    let groups: [(&str, &str, Vec<&ExperimentOutput>); 3] = [
        (
            "Under the paper's model (`model.preset = \"paper\"`)",
            PAPER_NOTE,
            input.outputs.iter().filter(paper).collect(),
        ),
        (
            "Every engine rule beyond the paper, as a sensitivity",
            RULES_NOTE,
            input
                .outputs
                .iter()
                .filter(|o| !paper(o) && rules(o))
                .collect(),
        ),
        (
            "Under the platform's defaults (`model.preset = \"platform\"`)",
            PLATFORM_NOTE,
            input
                .outputs
                .iter()
                .filter(|o| !paper(o) && !rules(o))
                .collect(),
        ),
    ];
    for (title, note, outputs) in groups {
        if outputs.is_empty() {
            continue;
        }
        md.push_str(&format!("## {title}\n\n{note}\n\n"));
        sections(&mut md, &mut n, &outputs, input.network_note);
    }

    md.push_str("## Run time\n\n");
    let header: Vec<String> = [
        "Experiment",
        "Runs (count)",
        "Computed (count)",
        "Reused (count)",
        "Wall time (s)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut rows: Vec<Vec<String>> = input
        .outputs
        .iter()
        .map(|o| {
            vec![
                rel_dir(o),
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
    let md = mark_verdicts_outside_glance(&md);
    let whole = format!("{head}## Contents\n\n{md}");
    let toc = contents(&whole);
    format!("{head}## Contents\n\n{toc}\n{md}")
}

/// The sentence below the heading of the paper's model's sections.
const PAPER_NOTE: &str =
    "These sections run the paper's rules as published (docs/model-choices.md, \"The two \
      presets\"): the published gap rule, the PATH organization rule (a CAV is in manual \
      control from its lane-change desire on), the spec's CACC law, no cooperative or \
      automated yielding; with only the engine rules without which the model cannot run. \
      Where a figure misses the paper's, the difference is this model's, not a tuning.";
/// … of the rules section.
const RULES_NOTE: &str =
    "Each row switches one of the engine's rules on over the paper's model; the last row \
      is the platform's defaults, the model of the sections after this one.";
/// … of the platform's sections.
const PLATFORM_NOTE: &str =
    "These sections run the engine's defaults: the paper's model with the documented \
      extensions that are on by default (the safe gap rule, automated organization with \
      the narrow hold, the field form of the CACC, 6.21, 6.22, automated yielding; \
      docs/model-choices.md).";

/// One numbered section per homogeneous-road experiment, one for the SR-99 experiments, then
/// one per experiment beyond the paper, at `###`.
fn sections(md: &mut String, n: &mut usize, outputs: &[&ExperimentOutput], network_note: &str) {
    let beyond = |o: &&&ExperimentOutput| o.name.part == Part::Beyond;
    for o in outputs.iter().filter(|o| !is_network(o) && !beyond(o)) {
        *n += 1;
        md.push_str(&format!("### {n}. {}\n\n", o.name.title()));
        md.push_str(&format!(
            "Why these figures differ from the paper's: `{NOTEBOOK}` in the repository \
             (where each figure stands against the paper's, and why).\n\n"
        ));
        md.push_str(&section(o, 2));
    }
    let network: Vec<&&ExperimentOutput> = outputs.iter().filter(|o| is_network(o)).collect();
    if !network.is_empty() {
        *n += 1;
        md.push_str(&format!(
            "### {n}. SR-99 corridor (paper Table 4, Figs. 6-8)\n\n{}\n\nWhy these figures \
             differ from the paper's: `{NOTEBOOK_SR99}` in the repository; how the corridor and \
             its demand were built: `docs/sr99-data.md`.\n\n",
            network_note.trim()
        ));
        for o in network {
            md.push_str(&format!("#### {}\n\n", o.name.title()));
            md.push_str(&section(o, 3));
        }
    }
    for o in outputs.iter().filter(beyond) {
        *n += 1;
        md.push_str(&format!("### {n}. {}\n\n", o.name.title()));
        md.push_str(&section(o, 2));
    }
}

/// The directory of an output relative to the report's (`paper/NAME` under the paper preset).
fn rel_dir(o: &ExperimentOutput) -> String {
    match o.settings.preset {
        Preset::Paper => format!("{}/{}", Preset::Paper.as_str(), o.name.as_str()),
        Preset::Platform => o.name.as_str().to_string(),
    }
}

/// [`mark_verdicts`] on the sections (the glance table has its symbols already).
fn mark_verdicts_outside_glance(md: &str) -> String {
    match md.find("\n### 1. ").and_then(|i| md[..i].rfind("\n## ")) {
        Some(i) => format!("{}{}", &md[..i], mark_verdicts(&md[i..])),
        None => md.to_string(),
    }
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
        rel_dir(o)
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
        md.push_str(&o.figures_md(&format!("{}/", rel_dir(o))));
    }
    md
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
    fn anchors_follow_github_and_the_contents_link_them() {
        let mut a = Anchors::default();
        assert_eq!(
            a.next("1. Capacity with and without the PD lane (paper Fig. 4)"),
            "1-capacity-with-and-without-the-pd-lane-paper-fig-4"
        );
        assert_eq!(a.next("Safety"), "safety");
        assert_eq!(a.next("Safety"), "safety-1");
        assert_eq!(a.next("L̄ & P_P"), "l̄--p_p");
        let md = "# T\n\n## Contents\n\n## 1. A `b`\n\n### Safety\n\n#### Deep\n\n## 2. C\n\n### Safety\n";
        assert_eq!(
            contents(md),
            "- [1. A b](#1-a-b)\n  - [Safety](#safety)\n- [2. C](#2-c)\n  - [Safety](#safety-1)\n"
        );
        let page = html(md, Path::new("."), "t");
        assert!(page.contains("<h2 id=\"1-a-b\">"), "{page}");
        assert!(page.contains("<h3 id=\"safety-1\">"), "{page}");
    }

    #[test]
    fn verdicts_carry_a_symbol_and_a_colour() {
        let md = format!("- {}: x\n- {}: y\n", verdict(true), verdict(false));
        assert_eq!(md, "- ✓ **holds**: x\n- ✗ **does not hold**: y\n");
        let page = html(&md, Path::new("."), "t");
        assert!(page.contains("<span class=\"fail\">✗ does not hold</span>: y"));
        assert!(page.contains("<span class=\"pass\">✓ holds</span>: x"));
        assert_eq!(
            mark_verdicts("- **holds**: a\n- **does not hold**: b\n"),
            "- ✓ **holds**: a\n- ✗ **does not hold**: b\n"
        );
    }

    #[test]
    fn utc_dates() {
        assert_eq!(utc(0), "1970-01-01 00:00 UTC");
        assert_eq!(utc(951_782_400), "2000-02-29 00:00 UTC");
        assert_eq!(utc(1_796_184_000 + 2_460), "2026-12-02 04:41 UTC");
    }

    #[test]
    fn headings_are_demoted() {
        assert_eq!(demote("# A\ntext\n## B"), "## A\ntext\n### B\n");
    }
}
