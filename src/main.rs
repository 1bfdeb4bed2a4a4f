//! The `aster` command line: check, run, inspect meshes, generate meshes.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use aster::run::driver::{self, RunOptions, EXIT_USAGE};

#[derive(Parser)]
#[command(
    name = "aster",
    version,
    about = "Runs code_aster command files (.comm) for nonlinear dynamic impact studies",
    long_about = "aster reads code_aster command files (.comm) and their MED meshes, checks every \
command and keyword against its catalogue before running anything, and produces the same \
message file (.mess), result file (.resu, with the OK/NOOK test report) and MED results \
as code_aster.\n\nExit codes: 0 success, 1 study error (syntax, check, run, or a NOOK test), \
2 usage error, 130/143 a run stopped by SIGINT/SIGTERM (what was computed is kept)."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Parse and check a command file without running it.
    ///
    /// Every error of the file is reported, with file, line, column, command
    /// and keyword path.
    Check {
        /// The command file (.comm).
        file: PathBuf,
    },
    /// Check and run a command file.
    ///
    /// Logical units are mapped from `<study>.export` next to the study
    /// (lines `F mmed path D 20`) and from `--unit`. Writes `<study>.mess`
    /// and `<study>.resu` next to the study unless `--out` is given.
    Run {
        /// The command file (.comm).
        file: PathBuf,
        /// Map a logical unit to a file, e.g. `--unit 20=med/sdnv103b.mmed`.
        #[arg(long = "unit", value_name = "N=PATH", value_parser = parse_unit)]
        units: Vec<(i64, PathBuf)>,
        /// A code_aster .export file (default: `<study>.export` next to the study).
        #[arg(long)]
        export: Option<PathBuf>,
        /// Directory for .mess, .resu and result files.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Do not echo the message log on the terminal.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Run a study several times and report where the time goes.
    ///
    /// Each run executes the whole study in this process, as `aster run`
    /// does (same .export and --unit resolution), with every output file
    /// written to a temporary directory. Prints the wall time of each run,
    /// then the median, min and max wall time, the median time per phase
    /// (element integration and assembly, law integration, factorization
    /// and solve, contact, output), Newton iterations, steps, step cuts,
    /// contact pairings and the peak memory. Exit code: that of the first
    /// failing run, if any.
    Bench {
        /// The command file (.comm).
        file: PathBuf,
        /// How many times to run the study.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..))]
        runs: u64,
        /// Also write the report as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Map a logical unit to a file, e.g. `--unit 20=med/sdnv103b.mmed`.
        #[arg(long = "unit", value_name = "N=PATH", value_parser = parse_unit)]
        units: Vec<(i64, PathBuf)>,
        /// A code_aster .export file (default: `<study>.export` next to the study).
        #[arg(long)]
        export: Option<PathBuf>,
        /// Threads of the element loops (default: rayon's, i.e. the CPU
        /// count or RAYON_NUM_THREADS). With 1, the element and law times
        /// split exactly.
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        threads: Option<u64>,
    },
    /// Print what a MED mesh file holds: counts per cell type, groups with
    /// their sizes, bounding box.
    Info {
        /// The MED file (.mmed, .med, .rmed).
        file: PathBuf,
        /// The mesh to describe (default: the first one in the file).
        #[arg(long)]
        mesh: Option<String>,
    },
    /// Draw a MED result file: the deformed mesh coloured by a field, or
    /// curves over time.
    ///
    /// Without --history: the mesh at instant --inst (default: the last),
    /// moved by --deform times the displacement DEPL (default 1, the true
    /// shape), cells filled by --field (default: V1 of VARI_ELGA, the
    /// cumulated plastic strain, where the file has it, else the norm of
    /// DEPL), over the initial shape in grey, with a colour bar. A 3D mesh
    /// is drawn by its skin seen in --plane (default xz: for the quarter
    /// bar, its symmetry plane). With --history: curves over time of
    /// nodal fields at one-node groups. Errors list what the file holds.
    /// See docs/post.md.
    Plot {
        /// The MED result file (.rmed, .med), written by IMPR_RESU, code_aster or SALOME.
        file: PathBuf,
        /// Instant drawn (default: the last of the field).
        #[arg(long, value_name = "T")]
        inst: Option<f64>,
        /// Field and component, e.g. VARI_ELGA:V1, DEPL:DY, DEPL:NORM.
        #[arg(long, value_name = "NAME:COMPONENT")]
        field: Option<String>,
        /// Displacement magnification (0: initial shape).
        #[arg(long, value_name = "SCALE")]
        deform: Option<f64>,
        /// Plane of the picture of a 3D mesh.
        #[arg(long, value_parser = ["xy", "xz", "yz"])]
        plane: Option<String>,
        /// A curve over time, e.g. A1:DEPL:DY (repeat for several curves).
        #[arg(long, value_name = "GROUP_NO:FIELD:COMPONENT")]
        history: Vec<String>,
        /// The mesh of the file (default: the first).
        #[arg(long)]
        mesh: Option<String>,
        /// The PNG written (default: next to the result, <name>.png or
        /// <name>_history.png).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Generate meshes.
    Mesh {
        #[command(subcommand)]
        what: MeshCommand,
    },
    /// Run a study of SDNV103 modelling B (docs/performance.md).
    ///
    /// convergence: meshes 2x8 to 40x160 and steps of 2 to 0.25 us, with
    /// Richardson estimates; stability: VY of A1 for four time schemes;
    /// hard-cases: penalties 1e5..1e14, steps of 2 and 4 us, undamped
    /// Newmark. Writes a Markdown table, CSVs and PNG plots into --out and
    /// splices the table into the document (docs/performance.md).
    Sweep {
        #[arg(value_parser = ["convergence", "stability", "hard-cases"])]
        what: String,
        /// Directory for the tables, CSVs and plots.
        #[arg(long, value_name = "DIR", default_value = "docs/performance")]
        out: PathBuf,
        /// The small version (2x8 and 5x20 meshes, steps of 2 and 1 us; 2x8 for the others).
        #[arg(long)]
        quick: bool,
        /// Longest run allowed, in seconds: a case predicted or measured to take
        /// longer is reported as skipped.
        #[arg(long, value_name = "SECONDS", default_value_t = 900.0)]
        budget: f64,
        /// The Markdown document whose `<!-- sweep:NAME -->` section is
        /// replaced (default: performance.md next to --out, if it exists).
        #[arg(long, value_name = "FILE")]
        doc: Option<PathBuf>,
        /// Keep the cases' meshes, command files and logs in this directory.
        #[arg(long, value_name = "DIR")]
        work: Option<PathBuf>,
    },
    /// Print reference documentation generated from the catalogue.
    Doc {
        /// What to print: `commands` (every command and keyword, Markdown).
        #[arg(value_parser = ["commands"])]
        what: String,
    },
}

#[derive(Subcommand)]
enum MeshCommand {
    /// The SDNV103 Taylor bar meshes (docs/mesh-generator.md).
    ///
    /// `--modelling B` gives the mesh of a modelling; otherwise give the kind
    /// and the cell counts: axis (n1 across, n2 along), quarter (n1, n2, n3
    /// angular cells over 90 degrees), tetra (n1 rings, n2 layers).
    Taylor {
        /// axis, quarter or tetra.
        #[arg(long, value_parser = ["axis", "quarter", "tetra"], required_unless_present = "modelling")]
        kind: Option<String>,
        /// The mesh of an SDNV103 modelling (A, B, D, E, F, G, H, I, J, K).
        #[arg(long, conflicts_with_all = ["kind", "n1", "n2", "n3", "linear"])]
        modelling: Option<char>,
        #[arg(long)]
        n1: Option<usize>,
        #[arg(long)]
        n2: Option<usize>,
        #[arg(long)]
        n3: Option<usize>,
        /// Linear cells (as CREA_MAILLAGE QUAD_LINE would give).
        #[arg(long)]
        linear: bool,
        /// The MED file to write.
        #[arg(short, long)]
        output: PathBuf,
    },
}

fn taylor(
    kind: Option<String>,
    modelling: Option<char>,
    n: [Option<usize>; 3],
    linear: bool,
    output: &std::path::Path,
) -> i32 {
    use aster::mesh::taylor::{generate, TaylorKind, TaylorParams};
    let params = match (modelling, kind.as_deref()) {
        (Some(m), _) => match TaylorParams::for_modelling(m) {
            Some(p) => p,
            None => {
                eprintln!("error: unknown modelling '{m}' (A, B, D, E, F, G, H, I, J or K)");
                return EXIT_USAGE;
            }
        },
        (None, Some(k)) => {
            let (kind, defaults) = match k {
                "axis" => (TaylorKind::Axis, [5, 20, 0]),
                "quarter" => (TaylorKind::Quarter, [5, 20, 6]),
                _ => (TaylorKind::Tetra, [3, 34, 0]),
            };
            TaylorParams {
                kind,
                n1: n[0].unwrap_or(defaults[0]),
                n2: n[1].unwrap_or(defaults[1]),
                n3: n[2].unwrap_or(defaults[2]),
                linear,
            }
        }
        (None, None) => return EXIT_USAGE,
    };
    let mesh = match generate(&params) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    if let Err(e) = aster::medio::write_mesh(output, &mesh) {
        eprintln!("error: {e}");
        return 1;
    }
    print!("{}", aster::medio::mesh_info(&mesh));
    0
}

fn sweep(
    what: &str,
    out: PathBuf,
    quick: bool,
    budget: f64,
    doc: Option<PathBuf>,
    work: Option<PathBuf>,
) -> i32 {
    use aster::sweep::{run_sweep, SweepKind, SweepOptions};
    let kind = match what {
        "convergence" => SweepKind::Convergence,
        "stability" => SweepKind::Stability,
        _ => SweepKind::HardCases,
    };
    if !(budget > 0.0 && budget.is_finite()) {
        eprintln!("error: --budget must be a positive number of seconds");
        return EXIT_USAGE;
    }
    let doc = doc.or_else(|| {
        let d = out.parent()?.join("performance.md");
        d.is_file().then_some(d)
    });
    let opts = SweepOptions {
        out,
        quick,
        budget,
        doc,
        work,
    };
    match run_sweep(kind, &opts, &mut |l| eprintln!("{l}")) {
        Ok(r) => {
            for f in &r.files {
                println!("{}", f.display());
            }
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    }
}

/// Options of `aster plot`, as given.
struct PlotArgs {
    file: PathBuf,
    inst: Option<f64>,
    field: Option<String>,
    deform: Option<f64>,
    plane: Option<String>,
    history: Vec<String>,
    mesh: Option<String>,
    output: Option<PathBuf>,
}

fn plot(a: PlotArgs) -> i32 {
    use aster::plot::{draw_history, draw_result, HistorySpec, PictureOptions, Plane, ResultData};
    let field = match a.field.as_deref().map(|f| {
        f.split_once(':')
            .map(|(n, c)| (n.trim().to_string(), c.trim().to_string()))
            .filter(|(n, c)| !n.is_empty() && !c.is_empty())
    }) {
        None => None,
        Some(Some(f)) => Some(f),
        Some(None) => {
            eprintln!("error: --field expects NAME:COMPONENT, e.g. VARI_ELGA:V1 or DEPL:NORM");
            return EXIT_USAGE;
        }
    };
    let specs: Vec<HistorySpec> = match a.history.iter().map(|s| HistorySpec::parse(s)).collect() {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    if let Some(d) = a.deform {
        if !d.is_finite() {
            eprintln!("error: --deform must be a finite number");
            return EXIT_USAGE;
        }
    }
    if !specs.is_empty()
        && (field.is_some() || a.inst.is_some() || a.deform.is_some() || a.plane.is_some())
    {
        eprintln!("error: --history draws curves over time; --field, --inst, --deform and --plane are for the picture of one instant");
        return EXIT_USAGE;
    }
    if !a.file.is_file() {
        eprintln!("error: {}: no such file", a.file.display());
        return 1;
    }
    let start = std::time::Instant::now();
    let data = match ResultData::read(&a.file, a.mesh.as_deref()) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return 1;
        }
    };
    let default_out = |suffix: &str| {
        let stem = a
            .file
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "result".into());
        a.file.with_file_name(format!("{stem}{suffix}.png"))
    };
    if !specs.is_empty() {
        let out = a.output.clone().unwrap_or_else(|| default_out("_history"));
        return match draw_history(&data, &specs, &out) {
            Ok(n) => {
                println!(
                    "{}: {} curves, {n} points ({:.2} s)",
                    out.display(),
                    specs.len(),
                    start.elapsed().as_secs_f64()
                );
                0
            }
            Err(e) => {
                eprintln!("error: {e}");
                1
            }
        };
    }
    let out = a.output.clone().unwrap_or_else(|| default_out(""));
    let opts = PictureOptions {
        field,
        inst: a.inst,
        deform: a.deform,
        plane: a.plane.as_deref().and_then(Plane::parse),
        ..PictureOptions::default()
    };
    match draw_result(&data, &opts, &out) {
        Ok(r) => {
            // A uniform field's bar range is padded around its value:
            // the value is what to report.
            let values = match r.uniform {
                Some(v) => format!(
                    "uniform value {v:e} (its range is below {:e} of it)",
                    aster::plot::picture::UNIFORM_RTOL
                ),
                None => format!("values {:e} .. {:e}", r.range.0, r.range.1),
            };
            println!(
                "{}: {} {} at t = {:e}, {values}, {} polygons, displacement x {} ({:.2} s)",
                out.display(),
                r.field,
                r.component,
                r.time,
                r.faces,
                r.deform,
                start.elapsed().as_secs_f64()
            );
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    }
}

fn parse_unit(s: &str) -> Result<(i64, PathBuf), String> {
    let (u, p) = s
        .split_once('=')
        .ok_or_else(|| format!("expected N=PATH, found '{s}'"))?;
    let u: i64 = u
        .trim()
        .parse()
        .map_err(|_| format!("the logical unit must be an integer, found '{u}'"))?;
    if p.is_empty() {
        return Err("empty path".into());
    }
    Ok((u, PathBuf::from(p)))
}

/// The stack of the pool threads that run a study: the main thread's
/// usual 8 MiB (a pool thread's default is 2 MiB).
const RUN_STACK_BYTES: usize = 8 << 20;

fn main() -> ExitCode {
    aster::interrupt::default_sigpipe();
    let cli = Cli::parse();
    let mut stdout = std::io::stdout();
    let code = match cli.command {
        Command::Check { file } => driver::check_file(&file, &mut stdout),
        Command::Run {
            file,
            units,
            export,
            out,
            quiet,
        } => {
            // SIGINT/SIGTERM stop the run cleanly, keeping what was
            // computed (docs/dynamics.md, "Stopping a run").
            if let Err(e) = aster::interrupt::install() {
                eprintln!("warning: {e}; a signal will kill the run without saving it");
            }
            let opts = RunOptions {
                comm: file,
                units,
                export,
                out_dir: out,
                verbose: !quiet,
            };
            // The study runs on a thread of the pool, as `aster bench`
            // runs it: an element loop started from a pool thread shares
            // its work with the other threads directly, where one started
            // from outside the pool hands the whole loop over and sleeps
            // until it is done (a wake-up of two threads per loop, and
            // three threads on two cores). docs/performance.md, "The
            // explicit step's cost".
            match rayon::ThreadPoolBuilder::new()
                .stack_size(RUN_STACK_BYTES)
                .build()
            {
                Ok(pool) => pool.install(|| driver::run_file(&opts, &mut stdout)),
                Err(e) => {
                    eprintln!(
                        "warning: cannot start the thread pool ({e}); running from the main thread"
                    );
                    driver::run_file(&opts, &mut stdout)
                }
            }
        }
        Command::Bench {
            file,
            runs,
            json,
            units,
            export,
            threads,
        } => aster::bench::harness::bench(
            &aster::bench::harness::BenchOptions {
                run: RunOptions {
                    comm: file,
                    units,
                    export,
                    out_dir: None,
                    verbose: false,
                },
                runs: runs as usize,
                json,
                threads: threads.map(|t| t as usize),
            },
            &mut stdout,
        ),
        Command::Info { file, mesh } => match aster::medio::read_mesh(&file, mesh.as_deref()) {
            Ok(m) => {
                print!("{}", aster::medio::mesh_info(&m));
                0
            }
            Err(e) => {
                eprintln!("error: {e}");
                if file.is_file() {
                    1
                } else {
                    EXIT_USAGE
                }
            }
        },
        Command::Plot {
            file,
            inst,
            field,
            deform,
            plane,
            history,
            mesh,
            output,
        } => plot(PlotArgs {
            file,
            inst,
            field,
            deform,
            plane,
            history,
            mesh,
            output,
        }),
        Command::Mesh {
            what:
                MeshCommand::Taylor {
                    kind,
                    modelling,
                    n1,
                    n2,
                    n3,
                    linear,
                    output,
                },
        } => taylor(kind, modelling, [n1, n2, n3], linear, &output),
        Command::Sweep {
            what,
            out,
            quick,
            budget,
            doc,
            work,
        } => sweep(&what, out, quick, budget, doc, work),
        Command::Doc { what } => match what.as_str() {
            "commands" => {
                print!(
                    "{}",
                    aster::catalog::doc::commands_markdown(&aster::commands::all())
                );
                0
            }
            _ => EXIT_USAGE,
        },
    };
    ExitCode::from(code as u8)
}
