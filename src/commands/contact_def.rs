//! DEFI_CONTACT's checked keywords turned into the contact engine's
//! [`ContactDef`]: the command language stays above the engine, which
//! only sees the resolved definition. Every error names the keyword it is
//! about; what the engine does not implement is refused, never ignored.

use crate::catalog::args::Args;
use crate::contact::{
    continuous, is_contact_surface, ContactDef, ContactZone, Coulomb, DiscreteAlgo, MidTie,
    ReacGeom,
};
use crate::diag::Diagnostic;
use crate::mesh::{CellType, Mesh};
use crate::nonlinear::explicit_contact::Enforcement;

impl ContactDef {
    /// Builds the definition from DEFI_CONTACT's checked keywords on the
    /// model's mesh. Every error names the keyword it is about.
    pub fn from_args(args: &Args, mesh: &Mesh) -> Result<ContactDef, Diagnostic> {
        build(args, mesh, false)
    }

    /// The definition for an explicit DYNA_NON_LINE (an aster extension:
    /// code_aster refuses contact in explicit dynamics): DISCRETE only,
    /// ALGO_CONT='PENALISATION' (E_N, and E_T with friction) or
    /// 'CONTRAINTE' enforced kinematically, Coulomb friction in both.
    pub fn explicit_from_args(
        args: &Args,
        mesh: &Mesh,
    ) -> Result<(ContactDef, Enforcement), Diagnostic> {
        if args.text("FORMULATION").unwrap_or("DISCRETE") != "DISCRETE" {
            return Err(args.not_implemented(
                "FORMULATION",
                "contact in explicit dynamics with a formulation other than 'DISCRETE'",
            ));
        }
        let def = build(args, mesh, true)?;
        let kinematic = args
            .facts("ZONE")
            .first()
            .and_then(|z| z.text("ALGO_CONT"))
            .unwrap_or("CONTRAINTE")
            == "CONTRAINTE";
        Ok((
            def,
            if kinematic {
                Enforcement::Kinematic
            } else {
                Enforcement::Penalty
            },
        ))
    }
}

/// DIST_MAIT + DIST_ESCL of every discrete zone, per slave node, into
/// `def` (code_aster's `cfdist`: both functions of X, Y, Z evaluated at
/// the contact point and added; the gap is the geometric one less their
/// sum). Evaluated once, at the slave node's initial coordinates: a
/// function of the position is read where the node starts, not where it
/// has moved (the same for a constant, DEFI_CONSTANTE, the common case).
/// A function of INST is refused, as is a thickness with
/// FORMULATION='CONTINUE'.
pub fn set_user_gaps(
    study: &crate::study::Study,
    args: &Args,
    def: &mut ContactDef,
    mesh: &Mesh,
) -> Result<(), Diagnostic> {
    use crate::concepts::ConceptData;
    let continuous = args.text("FORMULATION") == Some("CONTINUE");
    for (k, z) in args.facts("ZONE").iter().enumerate() {
        let mut funcs = Vec::new();
        for key in ["DIST_MAIT", "DIST_ESCL"] {
            let Some(name) = z.concept(key) else {
                continue;
            };
            let f = match study.concepts.data(name) {
                Some(ConceptData::Function(f)) => f,
                _ => return Err(z.error(key, format!("the function {name} holds no data"))),
            };
            if f.ordinates.iter().all(|&y| y == 0.0) {
                continue;
            }
            if continuous {
                return Err(z.not_implemented(
                    key,
                    &format!("{key}={name}: a fictitious thickness with FORMULATION='CONTINUE' (FORMULATION='DISCRETE' takes it)"),
                ));
            }
            let axis = match f.para.as_str() {
                "TOUTPARA" => None,
                "X" => Some(0),
                "Y" => Some(1),
                "Z" => Some(2),
                other => {
                    return Err(z.not_implemented(
                        key,
                        &format!("{key}={name}: a thickness function of {other}; functions of X, Y, Z or constants (DEFI_CONSTANTE) are taken"),
                    ))
                }
            };
            funcs.push((key, name, f, axis));
        }
        if funcs.is_empty() {
            continue;
        }
        let Some(zone) = def.zones.get_mut(k) else {
            continue;
        };
        for &s in &zone.slave_nodes {
            let mut total = 0.0;
            for (key, name, f, axis) in &funcs {
                let x = axis.map_or(0.0, |a| mesh.coords[s][a]);
                total += f.eval(x).map_err(|m| {
                    z.error(
                        key,
                        format!(
                            "{key}={name} at slave node N{} ({}): {m}",
                            s + 1,
                            axis.map_or("constant", |a| ["X", "Y", "Z"][a])
                        ),
                    )
                })?;
            }
            zone.user_gap.insert(s, total);
        }
    }
    Ok(())
}

fn build(args: &Args, mesh: &Mesh, explicit: bool) -> Result<ContactDef, Diagnostic> {
    {
        let formulation = args.text("FORMULATION").unwrap_or("DISCRETE");
        match formulation {
            "DISCRETE" | "CONTINUE" => {}
            "LIAISON_UNIL" => {
                return Err(args.not_implemented(
                    "FORMULATION",
                    "unilateral linear conditions (FORMULATION='LIAISON_UNIL'); only 'DISCRETE' penalised contact is available",
                ))
            }
            other => {
                return Err(args.error(
                    "FORMULATION",
                    format!("FORMULATION='{other}' is not supported"),
                ))
            }
        }
        if mesh.dim != 2 && mesh.dim != 3 {
            return Err(args.error(
                "",
                format!(
                    "contact needs a 2D or 3D mesh, {} has dimension {}",
                    mesh.name, mesh.dim
                ),
            ));
        }
        let friction = args.text("FROTTEMENT") == Some("COULOMB");
        if args.text("LISSAGE") == Some("OUI") {
            return Err(args.not_implemented("LISSAGE", "normal smoothing (LISSAGE='OUI')"));
        }
        let reac_geom = reac_geom(args)?;
        let zones = args.facts("ZONE");
        if zones.is_empty() {
            return Err(args.error("ZONE", "at least one ZONE is required"));
        }
        let continuous = formulation == "CONTINUE";
        let czones = if continuous {
            Some(
                zones
                    .iter()
                    .map(|z| continuous_zone(z, mesh, friction))
                    .collect::<Result<Vec<_>, _>>()?,
            )
        } else {
            None
        };
        let algo = discrete_algo(zones, continuous || explicit)?;
        let mut zones = zones
            .iter()
            .map(|z| zone(z, mesh, friction, continuous, explicit))
            .collect::<Result<Vec<_>, _>>()?;
        let ties = if algo == DiscreteAlgo::ActiveSet && mesh.dim == 3 {
            quad8_ties(&mut zones, mesh)
        } else {
            Vec::new()
        };
        let continuous = match czones {
            None => None,
            Some(czones) => Some(continuous_def(args, czones)?),
        };
        Ok(ContactDef {
            dim: mesh.dim,
            friction,
            reac_geom,
            algo,
            ties,
            zones,
            continuous,
        })
    }
}

/// The discrete method's ALGO_CONT, one for all zones (DEFI_CONTACT's
/// `same_algorithm` check, repeated here for a definition built without
/// the command). `other`: continuous or explicit contact, which read
/// ALGO_CONT their own way.
fn discrete_algo(zones: &[Args], other: bool) -> Result<DiscreteAlgo, Diagnostic> {
    if other {
        return Ok(DiscreteAlgo::Penalty);
    }
    super::defi_contact::same_algorithm(zones)?;
    Ok(
        if zones[0].text("ALGO_CONT").unwrap_or("CONTRAINTE") == "CONTRAINTE" {
            DiscreteAlgo::ActiveSet
        } else {
            DiscreteAlgo::Penalty
        },
    )
}

/// code_aster's `elimcq`/`cacoeq` for the active-set discrete method: each
/// mid-side node (5 to 8) of a QUAD8 slave cell whose edge's three nodes
/// are all slave nodes of the zone (none in SANS_GROUP_NO/SANS_GROUP_MA)
/// is tied to the edge's vertices and leaves the slave nodes. TRIA6 and
/// QUAD9 faces are left as they are, as in code_aster.
fn quad8_ties(zones: &mut [ContactZone], mesh: &Mesh) -> Vec<MidTie> {
    const EDGES: [(usize, usize, usize); 4] = [(4, 0, 1), (5, 1, 2), (6, 2, 3), (7, 3, 0)];
    let mut ties: Vec<MidTie> = Vec::new();
    for zone in zones.iter_mut() {
        let cells = mesh
            .cell_groups
            .get(&zone.slave_group)
            .map(Vec::as_slice)
            .unwrap_or(&[]);
        let mut tied = Vec::new();
        for &c in cells {
            let cell = &mesh.cells[c];
            if cell.kind != CellType::Quad8 {
                continue;
            }
            for (m, a, b) in EDGES {
                let [m, a, b] = [cell.nodes[m], cell.nodes[a], cell.nodes[b]];
                let slave = |n: usize| zone.slave_nodes.binary_search(&n).is_ok();
                if slave(m) && slave(a) && slave(b) {
                    tied.push(m);
                    if !ties.iter().any(|t| t.mid == m) {
                        ties.push(MidTie {
                            mid: m,
                            ends: [a, b],
                        });
                    }
                }
            }
        }
        tied.sort_unstable();
        zone.slave_nodes.retain(|n| tied.binary_search(n).is_err());
    }
    ties
}

fn reac_geom(args: &Args) -> Result<ReacGeom, Diagnostic> {
    Ok(match args.text("REAC_GEOM").unwrap_or("AUTOMATIQUE") {
        "CONTROLE" => {
            let n = args.int("NB_ITER_GEOM").unwrap_or(2);
            if n < 0 {
                return Err(args.error(
                    "NB_ITER_GEOM",
                    format!("NB_ITER_GEOM must be >= 0, got {n}"),
                ));
            }
            if n == 0 {
                ReacGeom::Sans
            } else {
                ReacGeom::Controle {
                    nb_iter_geom: n as usize,
                }
            }
        }
        "SANS" => ReacGeom::Sans,
        _ => {
            let n = args.int("ITER_GEOM_MAXI").unwrap_or(10);
            if n < 1 {
                return Err(args.error(
                    "ITER_GEOM_MAXI",
                    format!("ITER_GEOM_MAXI must be >= 1, got {n}"),
                ));
            }
            let r = args.real("RESI_GEOM").unwrap_or(0.01);
            if r.is_nan() || r <= 0.0 {
                return Err(args.error("RESI_GEOM", format!("RESI_GEOM must be > 0, got {r:e}")));
            }
            ReacGeom::Automatique {
                iter_geom_maxi: n as usize,
                resi_geom: r,
            }
        }
    })
}

/// Cells of a group, or an error naming the keyword and the nearest group.
fn cell_group<'m>(
    z: &Args,
    key: &str,
    name: &str,
    mesh: &'m Mesh,
) -> Result<&'m [usize], Diagnostic> {
    match mesh.cell_groups.get(name) {
        Some(c) => Ok(c),
        None => {
            let names: Vec<&str> = mesh.cell_groups.keys().map(String::as_str).collect();
            Err(z
                .error(
                    key,
                    format!("the mesh {} has no cell group '{name}'", mesh.name),
                )
                .choices(name, &names))
        }
    }
}

/// The top-level keywords of the continuous formulation.
fn continuous_def(
    args: &Args,
    zones: Vec<continuous::ContinuousZone>,
) -> Result<continuous::ContinuousDef, Diagnostic> {
    use continuous::Resolution;
    let reso = |key: &str| -> Result<Resolution, Diagnostic> {
        match args.text(key).unwrap_or("NEWTON") {
            "NEWTON" => Ok(Resolution::Newton),
            "POINT_FIXE" => Ok(Resolution::PointFixe),
            other => Err(args.error(key, format!("{key}='{other}' is not supported"))),
        }
    };
    let algo_reso_cont = reso("ALGO_RESO_CONT")?;
    let algo_reso_frot = reso("ALGO_RESO_FROT")?;
    let algo_reso_geom = reso("ALGO_RESO_GEOM")?;
    let iter_frot_maxi = if algo_reso_frot == Resolution::PointFixe {
        let n = args.int("ITER_FROT_MAXI").unwrap_or(10);
        if n < 1 {
            return Err(args.error(
                "ITER_FROT_MAXI",
                format!("ITER_FROT_MAXI must be >= 1, got {n}"),
            ));
        }
        n as usize
    } else {
        0
    };
    let iter_cont_maxi = if algo_reso_cont == Resolution::PointFixe {
        match args.text("ITER_CONT_TYPE").unwrap_or("MAXI") {
            "MAXI" => {
                let n = args.int("ITER_CONT_MAXI").unwrap_or(30);
                if n < 1 {
                    return Err(args.error(
                        "ITER_CONT_MAXI",
                        format!("ITER_CONT_MAXI must be >= 1, got {n}"),
                    ));
                }
                n as usize
            }
            other => {
                return Err(args.not_implemented(
                    "ITER_CONT_TYPE",
                    &format!("ITER_CONT_TYPE='{other}'; only 'MAXI' is available"),
                ))
            }
        }
    } else {
        0
    };
    let resi_geom = args.real("RESI_GEOM").unwrap_or(match algo_reso_geom {
        Resolution::Newton => 1e-6,
        Resolution::PointFixe => 1e-2,
    });
    let resi_frot = args.real("RESI_FROT").unwrap_or(1e-4);
    for (key, v) in [("RESI_GEOM", resi_geom), ("RESI_FROT", resi_frot)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(args.error(key, format!("{key} must be > 0, got {v:e}")));
        }
    }
    Ok(continuous::ContinuousDef {
        algo_reso_cont,
        algo_reso_frot,
        algo_reso_geom,
        resi_geom,
        resi_frot,
        iter_cont_maxi,
        iter_frot_maxi,
        zones,
    })
}

/// The continuous keywords of one ZONE; what is not built is refused.
fn continuous_zone(
    z: &Args,
    mesh: &Mesh,
    friction: bool,
) -> Result<continuous::ContinuousZone, Diagnostic> {
    use continuous::ContactInit;
    match z.text("ALGO_CONT").unwrap_or("STANDARD") {
        "STANDARD" => {}
        other => {
            return Err(z.not_implemented(
                "ALGO_CONT",
                &format!("ALGO_CONT='{other}' in the continuous formulation; only the augmented Lagrangian (ALGO_CONT='STANDARD') is available"),
            ))
        }
    }
    if let Some(a) = z.text("ALGO_FROT") {
        if a != "STANDARD" {
            return Err(z.not_implemented(
                "ALGO_FROT",
                &format!("ALGO_FROT='{a}' in the continuous formulation; only ALGO_FROT='STANDARD' is available"),
            ));
        }
    }
    if let Some(i) = z.text("INTEGRATION") {
        if i != "AUTO" {
            return Err(z.not_implemented(
                "INTEGRATION",
                &format!("INTEGRATION='{i}'; only the nodal contact points of INTEGRATION='AUTO' are available"),
            ));
        }
    }
    if let Some(a) = z.text("ADAPTATION") {
        if a != "CYCLAGE" && a != "NON" {
            return Err(z.not_implemented(
                "ADAPTATION",
                &format!("ADAPTATION='{a}' (automatic coefficients); only 'CYCLAGE' and 'NON' are available"),
            ));
        }
    }
    for (key, ok) in [
        ("GLISSIERE", "NON"),
        ("GRAND_GLIS", "NON"),
        ("LISSAGE", "NON"),
    ] {
        if let Some(v) = z.text(key) {
            if v != ok {
                return Err(z.not_implemented(key, &format!("{key}='{v}'")));
            }
        }
    }
    if z.has("SANS_GROUP_NO_FR") {
        return Err(z.not_implemented("SANS_GROUP_NO_FR", "nodes without friction"));
    }
    let positive = |key: &str, default: f64| -> Result<f64, Diagnostic> {
        let v = z.real(key).unwrap_or(default);
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(z.error(key, format!("{key} must be > 0, got {v:e}")))
        }
    };
    let coef_cont = positive("COEF_CONT", 100.0)?;
    let coef_frot = positive("COEF_FROT", 100.0)?;
    let mu = if friction {
        let mu = z
            .real("COULOMB")
            .ok_or_else(|| z.error("COULOMB", "COULOMB is required with FROTTEMENT='COULOMB'"))?;
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(z.error("COULOMB", format!("COULOMB must be >= 0, got {mu:e}")));
        }
        Some(mu)
    } else {
        None
    };
    let contact_init = match z.text("CONTACT_INIT").unwrap_or("INTERPENETRE") {
        "OUI" => ContactInit::Oui,
        "NON" => ContactInit::Non,
        _ => ContactInit::Interpenetre,
    };
    let name = z
        .text("GROUP_MA_ESCL")
        .ok_or_else(|| z.error("GROUP_MA_ESCL", "GROUP_MA_ESCL is required"))?;
    let slave_cells = cell_group(z, "GROUP_MA_ESCL", name, mesh)?.to_vec();
    // INTEGRATION='AUTO' on a quadratic face puts the contact points at
    // Gauss (TRIA6) or Simpson (QUAD8, with its centre) points, which
    // couple the multipliers of a cell: not built.
    if let Some(&c) = slave_cells
        .iter()
        .find(|&&c| matches!(mesh.cells[c].kind, CellType::Tria6 | CellType::Quad8))
    {
        return Err(z.not_implemented(
            "GROUP_MA_ESCL",
            &format!(
                "continuous contact on {} slave faces (their contact points are not the nodes); only TRIA3/QUAD4 slave faces in 3D",
                mesh.cells[c].kind.aster_name()
            ),
        ));
    }
    Ok(continuous::ContinuousZone {
        slave_cells,
        coef_cont,
        coef_frot,
        mu,
        seuil_init: z.real("SEUIL_INIT"),
        contact_init,
        cyclage: z.text("ADAPTATION").unwrap_or("CYCLAGE") == "CYCLAGE",
    })
}

fn zone(
    z: &Args,
    mesh: &Mesh,
    friction: bool,
    continuous: bool,
    explicit: bool,
) -> Result<ContactZone, Diagnostic> {
    // Keywords whose meaning aster does not implement: refuse, never ignore.
    for key in ["MAILLE_MAIT", "MAILLE_ESCL", "SANS_NOEUD", "SANS_MAILLE"] {
        if z.given(key) {
            return Err(z.not_implemented(key, "cells and nodes are designated by groups"));
        }
    }
    let unsupported: [(&str, &str, &str); 5] = [
        ("APPARIEMENT", "MAIT_ESCL", "NODAL pairing"),
        ("NORMALE", "MAIT", "a normal from the slave surface"),
        ("VECT_MAIT", "AUTO", "an imposed master normal"),
        (
            "TYPE_PROJECTION",
            "ORTHOGONALE",
            "a fixed projection direction",
        ),
        (
            "RESOLUTION",
            "OUI",
            "pairing-only checks (RESOLUTION='NON')",
        ),
    ];
    for (key, ok, what) in unsupported {
        if let Some(v) = z.text(key) {
            if v != ok {
                return Err(z.not_implemented(key, what));
            }
        }
    }
    // DIST_MAIT / DIST_ESCL: DEFI_CONTACT let through only functions equal
    // to 0 everywhere (`defi_contact::zero_thickness`), which change no gap.
    let algo = z.text("ALGO_CONT").unwrap_or("CONTRAINTE");
    if continuous {
        return zone_groups(z, mesh, 0.0, None);
    }
    if explicit && algo == "CONTRAINTE" {
        // Kinematic enforcement: no penalty; COULOMB alone (E_T, required
        // by the catalogue with friction, is not used).
        let coulomb = if friction {
            let mu = z.real("COULOMB").ok_or_else(|| {
                z.error("COULOMB", "COULOMB is required with FROTTEMENT='COULOMB'")
            })?;
            if !(mu.is_finite() && mu >= 0.0) {
                return Err(z.error("COULOMB", format!("COULOMB must be >= 0, got {mu:e}")));
            }
            Some(Coulomb {
                mu,
                e_t: 0.0,
                coef_matr_frot: 0.0,
            })
        } else {
            None
        };
        return zone_groups(z, mesh, 0.0, coulomb);
    }
    if friction && algo != "PENALISATION" {
        return Err(z
            .error(
                "ALGO_CONT",
                format!(
                    "with FROTTEMENT='COULOMB' the discrete formulation needs ALGO_CONT='PENALISATION', not '{algo}' (code_aster CONTACT3_3)"
                ),
            )
            .note("the catalogue default of ALGO_CONT is 'CONTRAINTE': write ALGO_CONT='PENALISATION' and give E_N"));
    }
    if algo == "CONTRAINTE" {
        if z.text("GLISSIERE") == Some("OUI") {
            return Err(z.not_implemented(
                "GLISSIERE",
                "bilateral sliding (GLISSIERE='OUI': a link once closed stays closed)",
            ));
        }
        // The active set: exact conditions, no penalty (E_N unused).
        return zone_groups(z, mesh, 0.0, None);
    }
    if algo != "PENALISATION" {
        return Err(z.not_implemented(
            "ALGO_CONT",
            &format!("ALGO_CONT='{algo}'; the discrete formulation has 'CONTRAINTE' (active set) and 'PENALISATION' (with E_N)"),
        ));
    }
    let positive = |key: &str| -> Result<f64, Diagnostic> {
        let v = z
            .real(key)
            .ok_or_else(|| z.error(key, format!("{key} is required")))?;
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(z.error(key, format!("{key} must be > 0, got {v:e}")))
        }
    };
    let e_n = positive("E_N")?;
    let coulomb = if friction {
        let e_t = positive("E_T")?;
        let mu = z
            .real("COULOMB")
            .ok_or_else(|| z.error("COULOMB", "COULOMB is required with FROTTEMENT='COULOMB'"))?;
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(z.error("COULOMB", format!("COULOMB must be >= 0, got {mu:e}")));
        }
        let c = z.real("COEF_MATR_FROT").unwrap_or(0.0);
        if !(0.0..=1.0).contains(&c) {
            return Err(z.error(
                "COEF_MATR_FROT",
                format!("COEF_MATR_FROT must be in [0, 1], got {c:e}"),
            ));
        }
        Some(Coulomb {
            mu,
            e_t,
            coef_matr_frot: c,
        })
    } else {
        None
    };
    zone_groups(z, mesh, e_n, coulomb)
}

/// The groups, slave nodes and pairing options of a zone.
fn zone_groups(
    z: &Args,
    mesh: &Mesh,
    e_n: f64,
    coulomb: Option<Coulomb>,
) -> Result<ContactZone, Diagnostic> {
    let skin_dim = mesh.dim - 1;
    let allowed = if skin_dim == 1 {
        "SEG2/SEG3"
    } else {
        "TRIA3/TRIA6/QUAD4/QUAD8"
    };
    let mut groups = Vec::new();
    for key in ["GROUP_MA_MAIT", "GROUP_MA_ESCL"] {
        let name = z
            .text(key)
            .ok_or_else(|| z.error(key, format!("{key} is required")))?;
        let cells = cell_group(z, key, name, mesh)?;
        if cells.is_empty() {
            return Err(z.error(key, format!("the cell group '{name}' is empty")));
        }
        for &c in cells {
            let kind = mesh.cells[c].kind;
            let ok = is_contact_surface(kind, mesh.dim);
            if !ok {
                return Err(z.error(
                    key,
                    format!(
                        "group '{name}': cell {} is a {}; a contact surface of a {}D model is made of {allowed} cells",
                        c + 1,
                        kind.aster_name(),
                        mesh.dim
                    ),
                ));
            }
        }
        groups.push((name.to_string(), cells.to_vec()));
    }
    let (slave_group, slave_cells) = groups.pop().expect("two groups pushed");
    let (master_group, master_cells) = groups.pop().expect("two groups pushed");

    let mut excluded = vec![false; mesh.nnodes()];
    for name in z.texts("SANS_GROUP_NO") {
        let nodes = mesh.node_groups.get(name).ok_or_else(|| {
            let names: Vec<&str> = mesh.node_groups.keys().map(String::as_str).collect();
            z.error(
                "SANS_GROUP_NO",
                format!("the mesh {} has no node group '{name}'", mesh.name),
            )
            .choices(name, &names)
        })?;
        for &n in nodes {
            excluded[n] = true;
        }
    }
    for name in z.texts("SANS_GROUP_MA") {
        let cells = cell_group(z, "SANS_GROUP_MA", name, mesh)?;
        for n in mesh.nodes_of_cells(cells) {
            excluded[n] = true;
        }
    }
    let slave_nodes: Vec<usize> = mesh
        .nodes_of_cells(&slave_cells)
        .into_iter()
        .filter(|&n| !excluded[n])
        .collect();
    if slave_nodes.is_empty() {
        return Err(z.error(
            "GROUP_MA_ESCL",
            format!("no slave node is left in '{slave_group}' once SANS_GROUP_NO/SANS_GROUP_MA are removed"),
        ));
    }
    let tole = z.real("TOLE_PROJ_EXT").unwrap_or(0.5);
    let dist_appa = z.real("DIST_APPA").unwrap_or(-1.0);
    Ok(ContactZone {
        master_group,
        slave_group,
        master_cells,
        slave_nodes,
        e_n,
        friction: coulomb,
        tole_proj_ext: (tole >= 0.0).then_some(tole),
        dist_appa: (dist_appa > 0.0).then_some(dist_appa),
        user_gap: Default::default(),
    })
}
