//! Continuous contact (FORMULATION='CONTINUE') in DYNA_NON_LINE: the
//! generalised Newton (contact statuses, Coulomb friction and pairing
//! inside the iterations) converges quadratically on SDNV103 F's impact
//! step, read from the Newton table (INFO=2) of the whole study.

mod common;

#[test]
fn impact_step_converges_quadratically() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("contact_continuous_src");
    std::fs::create_dir_all(&dir).unwrap();
    let comm = std::fs::read_to_string(root.join("comm/sdnv103f.comm")).unwrap();
    let comm = comm.replace(
        "CONVERGENCE=_F(RESI_GLOB_MAXI=1.E-6, ITER_GLOB_MAXI=30),",
        "CONVERGENCE=_F(RESI_GLOB_MAXI=1.E-6, ITER_GLOB_MAXI=30), INFO=2,",
    );
    assert!(comm.contains("INFO=2"));
    std::fs::write(dir.join("f.comm"), comm).unwrap();
    std::fs::write(
        dir.join("f.export"),
        format!("F mmed {} D 20\n", root.join("med/sdnv103d.mmed").display()),
    )
    .unwrap();
    let run = common::run_study(dir.join("f.comm").to_str().unwrap(), "contact_continuous_f");
    assert_eq!(run.code, 0, "{}", run.term);
    let mess = run.file("f.mess");
    // Newton tables: rows "iter k RESI_GLOB_RELA x RESI_GLOB_MAXI y" (k from
    // 0, the prediction's residual, as code_aster numbers them), one
    // block per attempted step; the impact step is the first with 5 or
    // more iterations.
    let mut blocks: Vec<Vec<f64>> = Vec::new();
    let mut cur: Vec<f64> = Vec::new();
    for line in mess.lines() {
        let t: Vec<&str> = line.split_whitespace().collect();
        if t.len() >= 6 && t[0] == "iter" && t[4] == "RESI_GLOB_MAXI" {
            let k: usize = t[1].parse().unwrap();
            if k == 0 && !cur.is_empty() {
                blocks.push(std::mem::take(&mut cur));
            }
            cur.push(t[5].parse().unwrap());
        }
    }
    blocks.push(cur);
    let impact = blocks
        .iter()
        .find(|b| b.len() >= 5)
        .expect("an impact step with 5 iterations or more");
    // Above the round-off floor (1e-8 N), each of the last three
    // residuals is at most C times the square of the previous one, with
    // C = 1e-2 /N: quadratic convergence (a linear rate, r_k+1 = q r_k,
    // would break it as soon as r_k < q / C, i.e. below 1 N for q = 1e-2).
    let pairs: Vec<(f64, f64)> = impact
        .windows(2)
        .map(|w| (w[0], w[1]))
        .filter(|&(_, b)| b > 1e-8)
        .collect();
    assert!(pairs.len() >= 3, "{impact:?}");
    for &(a, b) in &pairs[pairs.len() - 3..] {
        assert!(b <= 1e-2 * a * a, "{a:e} -> {b:e} in {impact:?}");
    }
    // The last residual below 1 N falls to the floor in one iteration.
    let small = pairs.iter().rev().find(|&&(a, _)| a < 1.0);
    assert!(small.is_some_and(|&(a, b)| b <= 1e-2 * a * a), "{impact:?}");
    assert!(*impact.last().unwrap() <= 1e-6);
}
