//! The module's stack: 8 MiB, as a native main thread has, instead of
//! rustc's 1 MiB default for wasm (docs/web.md, "Limits").

fn main() {
    if std::env::var("CARGO_CFG_TARGET_ARCH").as_deref() == Ok("wasm32") {
        println!("cargo:rustc-link-arg-cdylib=-zstack-size=8388608");
    }
}
