//! The page's files, embedded: no request leaves the machine.

/// An embedded file served at `path`.
pub(crate) struct Asset {
    pub path: &'static str,
    pub media: &'static str,
    pub body: &'static str,
}

/// The page; `{{TOKEN}}` is replaced by the run's token.
pub(crate) const PAGE: &str = include_str!("page/index.html");

/// The scripts and style sheets.
pub(crate) static ASSETS: &[Asset] = &[
    Asset {
        path: "/app.js",
        media: "text/javascript; charset=utf-8",
        body: include_str!("page/app.js"),
    },
    Asset {
        path: "/style.css",
        media: "text/css; charset=utf-8",
        body: include_str!("page/style.css"),
    },
];

/// The asset served at `path`.
pub(crate) fn find(path: &str) -> Option<&'static Asset> {
    ASSETS.iter().find(|a| a.path == path)
}
