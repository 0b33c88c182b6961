//! The aligned plain-text table of the terminal report (`robocal
//! report`): columns sized to their widest cell, numbers right-aligned,
//! control characters from the report replaced so that a hostile serial
//! cannot drive the terminal.

use std::fmt::Write;

/// Spaces between columns.
const COLUMN_GAP: usize = 2;
/// Indentation of tables under their heading.
pub const INDENT: &str = "  ";

#[derive(Clone, Copy, PartialEq)]
pub enum Align {
    Left,
    Right,
}

/// Text with control characters (ANSI escapes, carriage returns) replaced.
pub fn printable(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// Columns sized to their widest cell; numbers right-aligned.
pub struct TextTable {
    header: Vec<String>,
    align: Vec<Align>,
    rows: Vec<Vec<String>>,
}

impl TextTable {
    pub fn new(columns: &[(&str, Align)]) -> Self {
        TextTable {
            header: columns.iter().map(|(h, _)| h.to_string()).collect(),
            align: columns.iter().map(|(_, a)| *a).collect(),
            rows: Vec::new(),
        }
    }

    pub fn row(&mut self, cells: Vec<String>) {
        self.rows
            .push(cells.into_iter().map(|c| printable(&c)).collect());
    }

    pub fn render(&self, out: &mut String) {
        let width = |i: usize| {
            let cells = self
                .rows
                .iter()
                .filter_map(|r| r.get(i))
                .chain([&self.header[i]]);
            cells.map(|c| c.chars().count()).max().unwrap_or(0)
        };
        let widths: Vec<usize> = (0..self.header.len()).map(width).collect();
        let line = |out: &mut String, cells: &[String]| {
            let mut text = String::from(INDENT);
            for (i, w) in widths.iter().enumerate() {
                let cell = cells.get(i).map(String::as_str).unwrap_or("");
                let pad = " ".repeat(w - cell.chars().count().min(*w));
                let gap = if i + 1 < widths.len() {
                    " ".repeat(COLUMN_GAP)
                } else {
                    String::new()
                };
                match self.align[i] {
                    Align::Left => text.push_str(&format!("{cell}{pad}{gap}")),
                    Align::Right => text.push_str(&format!("{pad}{cell}{gap}")),
                }
            }
            let _ = writeln!(out, "{}", text.trim_end());
        };
        line(out, &self.header);
        let total = widths.iter().sum::<usize>() + COLUMN_GAP * widths.len().saturating_sub(1);
        let _ = writeln!(out, "{INDENT}{}", "-".repeat(total));
        for row in &self.rows {
            line(out, row);
        }
    }
}

/// A blank line and a section heading.
pub fn heading(out: &mut String, text: &str) {
    let _ = writeln!(out, "\n{text}");
}
