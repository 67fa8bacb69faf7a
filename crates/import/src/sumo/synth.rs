//! Structure-aware SUMO networks for the fuzz target `sumo_shapes`, the scaling tests and
//! `scripts/sumo_scale.py`'s shapes (issue 48 item 6): the shapes that found D1-D4 (deep
//! nesting, many connections, long chains, many attributes) and extreme numbers, made from a
//! few bytes so that a fuzzer explores sizes and values instead of XML syntax.

use std::fmt::Write;

/// A motorway of `n` edges of `len` m with `lanes` lanes, each lane connected to the next
/// edge's same lane, or to all its lanes with `fanout`; `speed` (m/s) and `extra` attributes
/// (written on every lane) as given.
pub fn chain(n: usize, lanes: usize, len: &str, speed: &str, fanout: bool, extra: &str) -> String {
    let mut s = String::from("<net version=\"1.20\">\n");
    for k in 0..n {
        let _ = writeln!(
            s,
            "  <edge id=\"e{k}\" from=\"n{k}\" to=\"n{}\" type=\"highway.motorway\">",
            k + 1
        );
        for i in 0..lanes {
            let _ = writeln!(
                s,
                "    <lane id=\"e{k}_{i}\" index=\"{i}\" speed=\"{speed}\" length=\"{len}\"{extra}/>"
            );
        }
        s.push_str("  </edge>\n");
    }
    for k in 0..n.saturating_sub(1) {
        for i in 0..lanes {
            for j in 0..lanes {
                if fanout || i == j {
                    let _ = writeln!(
                        s,
                        "  <connection from=\"e{k}\" to=\"e{}\" fromLane=\"{i}\" toLane=\"{j}\" \
                         dir=\"s\"/>",
                        k + 1
                    );
                }
            }
        }
    }
    s.push_str("</net>\n");
    s
}

/// An element nested `depth` levels inside `<net>`.
pub fn deep(depth: usize) -> String {
    format!(
        "<net version=\"1.20\">\n{}{}\n</net>\n",
        "<a>".repeat(depth),
        "</a>".repeat(depth)
    )
}

/// Numbers a field of a SUMO file may hold that have broken parsers: huge, tiny, negative
/// zero, not finite, long digit strings, exponents at the ends of `f64`.
const NUMBERS: [&str; 16] = [
    "0",
    "-0",
    "1",
    "0.5",
    "33.33",
    "1e308",
    "1.8e308",
    "-1e308",
    "4.9e-324",
    "nan",
    "inf",
    "-inf",
    "99999999999999999999",
    "1e-300",
    "18446744073709551616",
    "100000000000000000000000000000000000000000000000000000000000000000000000000000000000000",
];

/// A network (and a routes file) from fuzzer bytes: the first byte picks the shape, the next
/// two a size, the rest numbers for lengths, speeds, the vehicle type and the flow (one in
/// eight extreme, the others plausible, so that most inputs reach the corridor and the demand).
/// Sizes reach 20,000 edges, 20,000 connections, 5,000 attributes and 65,535 levels: enough
/// that a quadratic step takes seconds (libFuzzer's timeout then reports it) while a linear
/// import takes milliseconds.
pub fn from_bytes(data: &[u8]) -> (String, String) {
    let at = |i: usize| data.get(i).copied().unwrap_or(0);
    let size = u16::from_le_bytes([at(1), at(2)]) as usize;
    let num = |i: usize, plain: &[&'static str]| -> &'static str {
        match at(i) {
            b @ 224.. => NUMBERS[b as usize % NUMBERS.len()],
            b => plain[b as usize % plain.len()],
        }
    };
    let len = num(3, &["1", "3", "10", "25"]);
    let speed = num(4, &["10", "22.22", "33.33"]);
    let (net, edges) = match at(0) % 5 {
        0 => (deep(size), 0),
        1 => {
            let n = size.clamp(1, 20_000);
            (chain(n, 2, len, speed, false, ""), n)
        }
        2 => {
            let n = size.clamp(2, 1_250);
            (chain(n, 4, len, speed, true, ""), n)
        }
        3 => {
            // Many attributes on each lane.
            let extra: String = (0..size.min(5_000))
                .map(|i| format!(" x{i}=\"{i}\""))
                .collect();
            (chain(4, 1, len, speed, false, &extra), 4)
        }
        _ => {
            let n = (size % 64).max(1);
            let lanes = 1 + at(9) as usize % 8;
            (chain(n, lanes, len, speed, at(10) % 2 == 0, ""), n)
        }
    };
    let routes = format!(
        "<routes><vType id=\"t\" length=\"{}\" accel=\"{}\"/><flow id=\"f\" type=\"t\" \
         begin=\"0\" end=\"{}\" vehsPerHour=\"{}\" from=\"e0\" to=\"e{}\"/></routes>",
        num(5, &["4.5", "5", "7.5"]),
        num(6, &["1", "2.6"]),
        num(7, &["600", "1800", "3600"]),
        num(8, &["600", "1800", "4000"]),
        edges.max(1) - 1
    );
    (net, routes)
}
