//! Compiles `proto/wbv.proto` into a serialized `FileDescriptorSet` (`$OUT_DIR/wbv.fds`) with
//! `protox`, so that no system `protoc` is needed; `src/record/proto.rs` embeds it and completes
//! `wbv.State` / `wbv.Links` per run.

fn main() {
    println!("cargo:rerun-if-changed=proto/wbv.proto");
    let fds = protox::compile(["wbv.proto"], ["proto"]).expect("proto/wbv.proto compiles");
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR set by cargo"));
    std::fs::write(out.join("wbv.fds"), prost::Message::encode_to_vec(&fds))
        .expect("write wbv.fds");
}
