//! The page's static files, embedded in the binary: the ES modules and the
//! style sheet under `src/serve/page/`, each served at its path there
//! (`page/engine/http.js` at `/engine/http.js`); and the HTML page, which
//! `routes.rs` serves with the per-run token put into it.

/// One embedded file: its URL path, media type and text.
pub(crate) struct Asset {
    pub path: &'static str,
    pub media: &'static str,
    pub body: &'static str,
}

/// The page: public code, the same for every run (no key, no file name).
pub(crate) const PAGE: &str = include_str!("page/index.html");

const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";

/// Every file the page loads. A module added under `page/` must be added
/// here (the test below says so).
pub(crate) static ASSETS: &[Asset] = &[
    Asset {
        path: "/style.css",
        media: CSS,
        body: include_str!("page/style.css"),
    },
    Asset {
        path: "/entry.js",
        media: JS,
        body: include_str!("page/entry.js"),
    },
    Asset {
        path: "/app.js",
        media: JS,
        body: include_str!("page/app.js"),
    },
    Asset {
        path: "/diagnostics.js",
        media: JS,
        body: include_str!("page/diagnostics.js"),
    },
    Asset {
        path: "/dom.js",
        media: JS,
        body: include_str!("page/dom.js"),
    },
    Asset {
        path: "/editor.js",
        media: JS,
        body: include_str!("page/editor.js"),
    },
    Asset {
        path: "/document.js",
        media: JS,
        body: include_str!("page/document.js"),
    },
    Asset {
        path: "/diff.js",
        media: JS,
        body: include_str!("page/diff.js"),
    },
    Asset {
        path: "/share.js",
        media: JS,
        body: include_str!("page/share.js"),
    },
    Asset {
        path: "/sharing.js",
        media: JS,
        body: include_str!("page/sharing.js"),
    },
    Asset {
        path: "/settings.js",
        media: JS,
        body: include_str!("page/settings.js"),
    },
    Asset {
        path: "/words.js",
        media: JS,
        body: include_str!("page/words.js"),
    },
    Asset {
        path: "/scrub.js",
        media: JS,
        body: include_str!("page/scrub.js"),
    },
    Asset {
        path: "/thumbs.js",
        media: JS,
        body: include_str!("page/thumbs.js"),
    },
    Asset {
        path: "/colours.js",
        media: JS,
        body: include_str!("page/colours.js"),
    },
    Asset {
        path: "/keys.js",
        media: JS,
        body: include_str!("page/keys.js"),
    },
    Asset {
        path: "/leaves.js",
        media: JS,
        body: include_str!("page/leaves.js"),
    },
    Asset {
        path: "/defines.js",
        media: JS,
        body: include_str!("page/defines.js"),
    },
    Asset {
        path: "/files.js",
        media: JS,
        body: include_str!("page/files.js"),
    },
    Asset {
        path: "/layout.js",
        media: JS,
        body: include_str!("page/layout.js"),
    },
    Asset {
        path: "/replay.js",
        media: JS,
        body: include_str!("page/replay.js"),
    },
    Asset {
        path: "/bigtree.js",
        media: JS,
        body: include_str!("page/bigtree.js"),
    },
    Asset {
        path: "/session.js",
        media: JS,
        body: include_str!("page/session.js"),
    },
    Asset {
        path: "/tools.js",
        media: JS,
        body: include_str!("page/tools.js"),
    },
    Asset {
        path: "/view.js",
        media: JS,
        body: include_str!("page/view.js"),
    },
    Asset {
        path: "/view3d.js",
        media: JS,
        body: include_str!("page/view3d.js"),
    },
    Asset {
        path: "/meshes.js",
        media: JS,
        body: include_str!("page/meshes.js"),
    },
    Asset {
        path: "/gl3d.js",
        media: JS,
        body: include_str!("page/gl3d.js"),
    },
    Asset {
        path: "/paint3d.js",
        media: JS,
        body: include_str!("page/paint3d.js"),
    },
    Asset {
        path: "/orbit.js",
        media: JS,
        body: include_str!("page/orbit.js"),
    },
    Asset {
        path: "/engine/index.js",
        media: JS,
        body: include_str!("page/engine/index.js"),
    },
    Asset {
        path: "/engine/http.js",
        media: JS,
        body: include_str!("page/engine/http.js"),
    },
];

/// The embedded file served at `path`, if any.
pub(crate) fn find(path: &str) -> Option<&'static Asset> {
    ASSETS.iter().find(|a| a.path == path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::{Path, PathBuf};

    fn page_dir() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("src/serve/page")
    }

    /// The files under `dir`, recursively, as URL paths (`/engine/http.js`).
    fn walk(dir: &Path, root: &Path, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                walk(&p, root, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().to_str().unwrap();
                out.push(format!("/{}", rel.replace('\\', "/")));
            }
        }
    }

    /// The relative module specifiers of `import ... from './x.js'` (and
    /// `'../x.js'`) in a module's text.
    fn imports(text: &str) -> Vec<&str> {
        let mut found = Vec::new();
        for line in text.lines() {
            let line = line.trim_start();
            if !line.starts_with("import ") {
                continue;
            }
            let Some((_, rest)) = line.rsplit_once(" from ") else {
                continue;
            };
            let rest = rest.trim().trim_end_matches(';');
            let spec = rest.trim_matches(|c| c == '\'' || c == '"');
            found.push(spec);
        }
        found
    }

    /// `spec` relative to the module at URL path `from`, as a URL path.
    fn resolve(from: &str, spec: &str) -> String {
        let mut parts: Vec<&str> = from.split('/').filter(|s| !s.is_empty()).collect();
        parts.pop();
        for piece in spec.split('/') {
            match piece {
                "." | "" => {}
                ".." => {
                    parts.pop();
                }
                p => parts.push(p),
            }
        }
        format!("/{}", parts.join("/"))
    }

    #[test]
    fn every_script_and_style_under_page_is_served() {
        let dir = page_dir();
        let mut files = Vec::new();
        walk(&dir, &dir, &mut files);
        let served: Vec<&str> = files
            .iter()
            .map(String::as_str)
            .filter(|f| f.ends_with(".js") || f.ends_with(".css"))
            .collect();
        assert!(served.len() >= 5, "{served:?}");
        for f in &served {
            let a = find(f).unwrap_or_else(|| panic!("{f} is not in assets::ASSETS"));
            let on_disk = std::fs::read_to_string(dir.join(&f[1..])).unwrap();
            assert_eq!(a.body, on_disk, "{f}: the table embeds another file");
            let media = if f.ends_with(".js") { JS } else { CSS };
            assert_eq!(a.media, media, "{f}");
        }
        // And nothing in the table is missing from the folder.
        for a in ASSETS {
            assert!(served.contains(&a.path), "{} is not under page/", a.path);
        }
    }

    #[test]
    fn every_module_import_names_a_served_module_and_modules_stay_small() {
        let mut seen = 0;
        for a in ASSETS.iter().filter(|a| a.path.ends_with(".js")) {
            for spec in imports(a.body) {
                assert!(
                    spec.starts_with("./") || spec.starts_with("../"),
                    "{}: `{spec}` is not a relative module path (the page loads only its own files)",
                    a.path
                );
                let target = resolve(a.path, spec);
                assert!(
                    find(&target).is_some(),
                    "{} imports `{spec}`, which is not served ({target} is not in assets::ASSETS)",
                    a.path
                );
                seen += 1;
            }
        }
        assert!(
            seen >= 5,
            "only {seen} imports found: is the import scan broken?"
        );
        assert_eq!(resolve("/engine/index.js", "./http.js"), "/engine/http.js");
        assert_eq!(resolve("/engine/http.js", "../dom.js"), "/dom.js");
        assert_eq!(resolve("/app.js", "./engine/index.js"), "/engine/index.js");
        // Modules of one concern each: none over 400 lines.
        for a in ASSETS.iter().filter(|a| a.path.ends_with(".js")) {
            let lines = a.body.lines().count();
            assert!(lines <= 400, "{} has {lines} lines", a.path);
        }
    }
}
