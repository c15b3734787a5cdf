//! Headless Chromium, to check that HTML reports show every picture in a real browser.

use std::path::Path;
use std::process::Command;

use super::{stderr, stdout};

/// The headless Chromium that `scripts/test` installs (`scripts/browser install`).
fn chromium() -> String {
    if let Ok(c) = std::env::var("DISCO_CHROMIUM") {
        return c;
    }
    for c in ["chromium", "chromium-browser"] {
        if Command::new(c)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
        {
            return c.to_string();
        }
    }
    panic!("no chromium for the report tests: run scripts/browser install (scripts/test does)");
}

/// Opens `html` in headless Chromium and returns (images on the page, images that loaded).
pub fn open_in_chromium(html: &Path) -> (usize, usize) {
    let profile = tempfile::tempdir().unwrap();
    let o = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--virtual-time-budget=10000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("file://{}", html.display()))
        .output()
        .expect("chromium runs");
    let dom = stdout(&o);
    let attr = |name: &str| -> usize {
        let key = format!("{name}=\"");
        let at = dom
            .find(&key)
            .unwrap_or_else(|| panic!("no {name} in the page: {}", stderr(&o)));
        dom[at + key.len()..]
            .split('"')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    (attr("data-images-total"), attr("data-images-loaded"))
}
