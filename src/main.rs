//! The `wbv` command: a thin shell over the library (see `wbv --help`).

fn main() -> std::process::ExitCode {
    wbv::cli::main()
}
