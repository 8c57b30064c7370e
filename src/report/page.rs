//! The report page being written: its sections, sub-headings and tables, each with an id,
//! and the table of contents that links to every one of them.

use super::layout::esc;
use std::collections::BTreeSet;
use std::fmt;

/// The attributes of the page's tables of numbers.
pub(super) const TABLE_ATTRS: &str =
    " border=\"1\" cellpadding=\"4\" style=\"border-collapse:collapse\"";

/// Line colours of the plots (viridis-like, then two warm ones).
pub(super) const PALETTE: [&str; 6] = [
    "#440154", "#3b528b", "#21918c", "#5ec962", "#c8a900", "#d1495b",
];

/// The id of the table of contents itself.
pub const CONTENTS_ID: &str = "contents";

/// One entry of the contents: depth (1 = section), id, text.
struct Entry {
    depth: usize,
    id: String,
    text: String,
}

/// The page's body and its contents.
#[derive(Default)]
pub struct Page {
    body: String,
    entries: Vec<Entry>,
    ids: BTreeSet<String>,
    /// Depth of the last heading (tables are listed one deeper).
    depth: usize,
}

impl Page {
    pub fn new() -> Page {
        Page::default()
    }

    /// A unique id made from `text`: lower-case ASCII letters and digits, runs of anything
    /// else as one `-`; `-2`, `-3`, … when taken.
    fn id_for(&mut self, text: &str) -> String {
        let mut slug = String::new();
        for c in text.chars() {
            if c.is_ascii_alphanumeric() {
                slug.push(c.to_ascii_lowercase());
            } else if !slug.ends_with('-') {
                slug.push('-');
            }
        }
        let slug = slug.trim_matches('-');
        let base = if slug.is_empty() { "part" } else { slug }.to_string();
        let mut id = base.clone();
        let mut k = 2;
        while id == CONTENTS_ID || self.ids.contains(&id) {
            id = format!("{base}-{k}");
            k += 1;
        }
        self.ids.insert(id.clone());
        id
    }

    fn entry(&mut self, depth: usize, text: &str) -> String {
        let id = self.id_for(text);
        self.entries.push(Entry {
            depth,
            id: id.clone(),
            text: text.to_string(),
        });
        id
    }

    /// Opens a `<section>` headed `title` (plain text), listed in the contents.
    pub fn section(&mut self, title: &str) {
        let id = self.entry(1, title);
        self.depth = 1;
        self.body
            .push_str(&format!("<section id=\"{id}\"><h2>{}</h2>\n", esc(title)));
    }

    /// Closes the section opened last.
    pub fn end_section(&mut self) {
        self.body.push_str("</section>\n");
    }

    /// An `<h3>` heading `title` (plain text), listed in the contents under its section.
    pub fn heading(&mut self, title: &str) {
        let id = self.entry(2, title);
        self.depth = 2;
        self.body
            .push_str(&format!("<h3 id=\"{id}\">{}</h3>\n", esc(title)));
    }

    /// Opens a `<table>` (attributes `attrs`) captioned `caption` (plain text), listed in
    /// the contents under the heading before it; close it with `</table>`.
    pub fn table(&mut self, caption: &str, attrs: &str) {
        let id = self.entry(self.depth + 1, caption);
        self.body.push_str(&format!(
            "<table id=\"{id}\"{attrs}><caption>{}</caption>",
            esc(caption)
        ));
    }

    pub fn push_str(&mut self, s: &str) {
        self.body.push_str(s);
    }

    /// The contents as nested lists of links.
    fn contents(&self) -> String {
        let mut out = format!("<nav id=\"{CONTENTS_ID}\"><h2>Contents</h2>");
        // per open list: whether an item of it is open
        let mut open: Vec<bool> = Vec::new();
        for e in &self.entries {
            while open.len() > e.depth {
                if open.pop() == Some(true) {
                    out.push_str("</li>");
                }
                out.push_str("</ul>");
            }
            while open.len() < e.depth {
                out.push_str("<ul>");
                open.push(false);
            }
            if open.last() == Some(&true) {
                out.push_str("</li>");
            }
            out.push_str(&format!("<li><a href=\"#{}\">{}</a>", e.id, esc(&e.text)));
            if let Some(o) = open.last_mut() {
                *o = true;
            }
        }
        while let Some(o) = open.pop() {
            if o {
                out.push_str("</li>");
            }
            out.push_str("</ul>");
        }
        out.push_str("</nav>\n");
        out
    }

    /// `head` (everything up to the contents), the contents, then the body.
    pub fn finish(self, head: &str) -> String {
        let mut out = String::from(head);
        out.push_str(&self.contents());
        out.push_str(&self.body);
        out
    }
}

impl fmt::Write for Page {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.body.push_str(s);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contents_nest_and_ids_are_unique() {
        let mut p = Page::new();
        p.section("filament-dfg / dfg");
        p.heading("Comparison with Karis' EnvBRDFApprox (mobile, 2014)");
        p.table("errors per channel", "");
        p.push_str("</table>");
        p.end_section();
        p.section("filament-dfg / dfg");
        p.section("Contents");
        p.end_section();
        let html = p.finish("<body>");
        assert!(html.contains("<section id=\"filament-dfg-dfg\">"));
        assert!(html.contains("<section id=\"filament-dfg-dfg-2\">"));
        assert!(html.contains("<section id=\"contents-2\">"));
        assert!(html.contains("<h3 id=\"comparison-with-karis-envbrdfapprox-mobile-2014\">"));
        assert!(html.contains("<table id=\"errors-per-channel\"><caption>"));
        let nav = &html[html.find("<nav").unwrap()..html.find("</nav>").unwrap()];
        assert_eq!(nav.matches("<ul>").count(), 3);
        assert_eq!(nav.matches("</ul>").count(), 3);
        assert_eq!(nav.matches("<li>").count(), nav.matches("</li>").count());
        assert!(nav.contains(
            "<ul><li><a href=\"#filament-dfg-dfg\">filament-dfg / dfg</a><ul><li><a href=\"#comparison"
        ));
    }
}
