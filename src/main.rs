//! The `mechbook` binary: everything lives in the library; see `cli`.

fn main() -> std::process::ExitCode {
    mechbook::cli::main()
}
