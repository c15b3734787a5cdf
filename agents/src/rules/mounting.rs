//! Where the pieces that leave the floor go, for the rule planner: a lamp onto a nightstand, a
//! TV onto its stand, a painting onto the wall above the bed.
//!
//! A piece leaves the floor when its asset says so (`support`) or its kind's mount does
//! ([`Kind::mount_for`]). Then:
//!
//! - **On a surface**: it goes onto the top of a piece its mount names (`on`, in order of
//!   preference), one that stays on the floor, is neither a seat nor a floor covering, is
//!   [`MIN_TOP_CM`]-[`MAX_TOP_CM`] high and has room left on its top: the pieces on it stand in
//!   rows along its width, and take at most [`TOP_USE`] of its area.
//!   Of those it takes the one holding fewest pieces of its own kind, then the best named, then
//!   the one holding fewest pieces at all: two lamps and two nightstands give a lamp to each,
//!   and a coffee machine joins the microwave on the counter rather than take the dining table.
//!   A kind whose pieces go `together` puts the best named first, then the fewest of its kind
//!   (both speakers on the TV's stand; four monitors over four desks). Bigger pieces choose
//!   first. With no such top,
//!   a piece whose mount says `or_wall` hangs on a wall (a TV across from the sofa); any other
//!   stays on the floor, and the notes say so.
//! - **On a wall**: it hangs centred above a piece its mount names (`above`): one that stays on
//!   the floor against a wall, no taller than [`MAX_UNDER_CM`], with nothing of another kind
//!   hung above it and room left over it (pieces of one kind hang above a piece in a row,
//!   [`ROW_GAP_CM`] apart, no wider than [`ROW_OVERHANG`] times the piece: three paintings above
//!   a sofa); the best named first, then one with nothing above it yet. With none, it hangs on a
//!   free stretch of wall (the designer finds one).
//!
//! A piece is named by its category, or by its kind when the category holds the name's last word
//! ([`Knowledge::named_rank`]): a "double vanity" is a vanity, the toilet of the same family of
//! fixtures is not.

use disco_core::geometry3d::is_seat;
use disco_core::scene::{SceneSpec, Support};

use crate::kinship::OwnWords;
use crate::knowledge::{Kind, Knowledge, Mount};

/// The lowest top (cm) a piece may stand on: lower is a footstool or a tray on the floor.
pub const MIN_TOP_CM: f64 = 25.0;

/// The highest top (cm) a piece may stand on: higher is a wardrobe's or a tall bookcase's top.
pub const MAX_TOP_CM: f64 = 125.0;

/// The share of a top's area the pieces standing on it may take together.
pub const TOP_USE: f64 = 0.75;

/// The tallest piece (cm) something hangs above: a wardrobe has no wall above it to speak of.
pub const MAX_UNDER_CM: f64 = 130.0;

/// Space (cm) between the pieces of a row hung above one piece.
pub const ROW_GAP_CM: f64 = 20.0;

/// How much wider than the piece below a row hung above it may be.
pub const ROW_OVERHANG: f64 = 1.1;

/// Where one piece goes off the floor, by asset index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mounted {
    /// On the top of this piece.
    On(usize),
    /// On a wall: centred above a piece, across from one (facing it), or on a free stretch.
    Wall {
        /// The piece it hangs above, centred.
        above: Option<usize>,
        /// The piece it hangs across from, facing it (a TV without a stand faces the sofa).
        across: Option<usize>,
    },
}

impl Mounted {
    /// The support the plan gives it.
    pub(crate) fn support(self) -> Support {
        match self {
            Mounted::On(_) => Support::Surface,
            Mounted::Wall { .. } => Support::Wall,
        }
    }
}

/// What the prompt asks of one piece's place off the floor ("a lamp on each nightstand", "the
/// painting above the sofa", "the TV on the wall").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Wish {
    /// Nothing.
    #[default]
    None,
    /// On the top of this piece.
    On(usize),
    /// Hung above this piece.
    Above(usize),
    /// On a wall.
    Wall,
}

/// The tallest piece (cm) the prompt may put on a top that its kind keeps on the floor.
pub const ASKED_ON_UP_TO_CM: f64 = 60.0;

/// The deepest piece (cm) the prompt may hang above another that its kind keeps on the floor.
pub const ASKED_ABOVE_DEPTH_CM: f64 = 15.0;

/// Where every piece of `scene` that leaves the floor goes (`None`: it stays on the floor), and
/// the notes on those that found no place off it. `against_wall` says which pieces stand with
/// their back on a wall (the plan's draft), `kinds` are the assets' kinds, `wishes` what the
/// prompt asks of each: a top or a piece to hang above, taken when it holds the piece (a small
/// piece the knowledge keeps on the floor too), or a wall for a piece that may hang on one.
pub(crate) fn mount_all(
    scene: &SceneSpec,
    kinds: &[Kind],
    against_wall: &[bool],
    wishes: &[Wish],
) -> (Vec<Option<Mounted>>, Vec<String>) {
    let n = kinds.len();
    let wish = |i: usize| wishes.get(i).copied().unwrap_or_default();
    let mounts: Vec<Option<Mount>> = scene
        .assets
        .iter()
        .zip(kinds)
        .enumerate()
        .map(|(i, (a, k))| {
            let own = k.mount_for(a);
            match (wish(i), a.support) {
                (_, Some(Support::Floor)) => None,
                (Wish::On(_), _) if own.is_none() && a.size[2] <= ASKED_ON_UP_TO_CM => {
                    Some(Mount::plain(Support::Surface))
                }
                (Wish::Above(_), _) if own.is_none() && a.size[1] <= ASKED_ABOVE_DEPTH_CM => {
                    Some(Mount::plain(Support::Wall))
                }
                _ => own,
            }
        })
        .collect();
    let stays = |j: usize| mounts[j].is_none();
    let own: Vec<OwnWords> = scene.assets.iter().map(OwnWords::of).collect();
    let mut out: Vec<Option<Mounted>> = vec![None; n];
    let mut notes = Vec::new();
    // Room used on each top (cm²), pieces of each kind on it, and what hangs above each piece.
    let mut used = vec![0.0_f64; n];
    let mut tops: Vec<Top> = vec![Top::default(); n];
    let mut same_kind: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    let mut pieces_on = vec![0_usize; n];
    // Over each piece: the kind hung above it and the width of its row.
    let mut hung_above: Vec<Option<(usize, f64)>> = vec![None; n];

    let mut order: Vec<usize> = (0..n).filter(|&i| mounts[i].is_some()).collect();
    let area = |i: usize| scene.assets[i].size[0] * scene.assets[i].size[1];
    order.sort_by(|&a, &b| area(b).total_cmp(&area(a)).then(a.cmp(&b)));

    for i in order {
        let Some(mount) = &mounts[i] else { continue };
        let asset = &scene.assets[i];
        match mount.support {
            Support::Floor => {}
            Support::Surface => {
                let kind_key = kind_index(kinds, i);
                let asked = match wish(i) {
                    Wish::On(t) => Some(t),
                    _ => None,
                }
                .filter(|&t| {
                    t != i
                        && stays(t)
                        && holds_things(scene, kinds, t)
                        && fits_on(scene, i, t, used[t], &tops[t]).is_some()
                });
                let wants_wall = wish(i) == Wish::Wall && mount.or_wall;
                let best = (0..n)
                    .filter(|_| !wants_wall)
                    .filter(|&j| j != i && stays(j) && holds_things(scene, kinds, j))
                    .filter_map(|j| {
                        surface_rank(scene, kinds, mount, j)
                            .or((asked == Some(j)).then_some(0))
                            .map(|r| (j, r))
                    })
                    .filter(|&(j, _)| fits_on(scene, i, j, used[j], &tops[j]).is_some())
                    .min_by_key(|&(j, rank)| {
                        let asked_first = usize::from(asked.is_some_and(|t| t != j));
                        // A top its own words name ("payment terminal on the front desk", a
                        // "steriliser" and the "sterilisation counter") before the others.
                        let stranger = usize::from(!own[i].kin(&own[j]));
                        let mine = same_kind[j]
                            .iter()
                            .find(|(k, _)| *k == kind_key)
                            .map_or(0, |(_, c)| *c);
                        if mount.together {
                            (asked_first, stranger, rank, mine, pieces_on[j], j)
                        } else {
                            (asked_first, stranger, mine, rank, pieces_on[j], j)
                        }
                    });
                if let Some((j, _)) = best {
                    if let Some(top) = fits_on(scene, i, j, used[j], &tops[j]) {
                        tops[j] = top;
                    }
                    used[j] += area(i);
                    pieces_on[j] += 1;
                    match same_kind[j].iter_mut().find(|(k, _)| *k == kind_key) {
                        Some((_, c)) => *c += 1,
                        None => same_kind[j].push((kind_key, 1)),
                    }
                    out[i] = Some(Mounted::On(j));
                } else if mount.or_wall {
                    let across = kinds[i].relate.as_ref().and_then(|r| {
                        (0..n)
                            .filter(|&j| j != i && stays(j))
                            .filter_map(|j| {
                                Knowledge::target_rank(&scene.assets[j], &kinds[j], &r.to)
                                    .map(|rank| (rank, j))
                            })
                            .min()
                            .map(|(_, j)| j)
                    });
                    out[i] = Some(Mounted::Wall {
                        above: None,
                        across,
                    });
                } else {
                    notes.push(format!(
                        "{} stands on the floor: no table, desk or counter of the room has room \
                         for it on top",
                        asset.name
                    ));
                }
            }
            Support::Wall => {
                let kind_key = kind_index(kinds, i);
                let width = asset.size[0];
                let room_over = |j: usize| match hung_above[j] {
                    None => true,
                    Some((k, row)) => {
                        k == kind_key
                            && row + ROW_GAP_CM + width <= ROW_OVERHANG * scene.assets[j].size[0]
                    }
                };
                let asked = match wish(i) {
                    Wish::Above(t) => Some(t),
                    _ => None,
                }
                .filter(|&t| t != i && stays(t) && !scene.assets[t].is_flat());
                let above = asked.or_else(|| {
                    (0..n)
                        .filter(|&j| j != i && stays(j) && against_wall[j] && room_over(j))
                        .filter(|&j| {
                            let s = &scene.assets[j];
                            !s.is_flat() && s.size[2] <= MAX_UNDER_CM
                        })
                        .filter_map(|j| {
                            Knowledge::named_rank(&scene.assets[j], &kinds[j], &mount.above)
                                .map(|rank| (rank, hung_above[j].is_some(), j))
                        })
                        .min()
                        .map(|(_, _, j)| j)
                });
                if let Some(j) = above {
                    hung_above[j] = Some(match hung_above[j] {
                        None => (kind_key, width),
                        Some((k, row)) => (k, row + ROW_GAP_CM + width),
                    });
                }
                out[i] = Some(Mounted::Wall {
                    above,
                    across: None,
                });
            }
        }
    }
    (out, notes)
}

/// A key for the kind of asset `i` (the index of the first asset of the same kind), so that
/// two lamps count as the same kind on a top.
fn kind_index(kinds: &[Kind], i: usize) -> usize {
    kinds
        .iter()
        .position(|k| k.names == kinds[i].names)
        .unwrap_or(i)
}

/// Whether piece `j` can hold things on its top: solid, not a seat, its top within
/// [`MIN_TOP_CM`]-[`MAX_TOP_CM`].
fn holds_things(scene: &SceneSpec, kinds: &[Kind], j: usize) -> bool {
    let s = &scene.assets[j];
    let h = s.size[2];
    !s.is_flat()
        && !kinds[j].seat
        && !is_seat(&s.category)
        && !is_seat(&s.name)
        && (MIN_TOP_CM..=MAX_TOP_CM).contains(&h)
}

/// How well piece `j` suits as the top for a piece of `mount` (lower is better): by the mount's
/// `on` list; a mount with no list (an asset that says `"surface"` of a kind the knowledge does
/// not mount) takes tables, desks and counters first, then any low piece.
fn surface_rank(scene: &SceneSpec, kinds: &[Kind], mount: &Mount, j: usize) -> Option<usize> {
    if !mount.on.is_empty() {
        return Knowledge::named_rank(&scene.assets[j], &kinds[j], &mount.on);
    }
    let worktop = kinds[j].seats.is_some()
        || kinds[j]
            .names
            .iter()
            .any(|n| ["table", "desk", "counter", "sideboard", "dresser"].contains(&n.as_str()));
    Some(if worktop { 0 } else { 1 })
}

/// The pieces on one top, as rows along its width from back to front: each row's depth and the
/// width its pieces take.
#[derive(Debug, Clone, Default)]
struct Top {
    rows: Vec<(f64, f64)>,
}

impl Top {
    /// The top with a `w` x `d` piece added on a `tw` x `td` top: beside the pieces of the first
    /// row it fits, else in a new row in front of them; `None` when neither has room.
    fn with(&self, w: f64, d: f64, tw: f64, td: f64) -> Option<Top> {
        let mut next = self.clone();
        if let Some(row) = next
            .rows
            .iter_mut()
            .find(|(depth, width)| d <= *depth && width + w <= tw)
        {
            row.1 += w;
            return Some(next);
        }
        let depth_used: f64 = next.rows.iter().map(|(depth, _)| depth).sum();
        (w <= tw && depth_used + d <= td).then(|| {
            next.rows.push((d, w));
            next
        })
    }
}

/// The top of asset `j` with asset `i` on it too, beside what is there already (`top`, and
/// `used` cm² in all), turned as the top or else a quarter; `None` when it has no room, or the
/// pieces would take more than [`TOP_USE`] of its area.
fn fits_on(scene: &SceneSpec, i: usize, j: usize, used: f64, top: &Top) -> Option<Top> {
    let [w, d, _] = scene.assets[i].size;
    let [tw, td, _] = scene.assets[j].size;
    if used + w * d > TOP_USE * tw * td {
        return None;
    }
    top.with(w, d, tw, td).or_else(|| top.with(d, w, tw, td))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::scene;

    fn mounted(s: &SceneSpec) -> Vec<Option<Mounted>> {
        let k = Knowledge::builtin();
        let kinds: Vec<Kind> = s.assets.iter().map(|a| k.kind_of(a)).collect();
        let walls: Vec<bool> = kinds.iter().map(|k| k.wall).collect();
        mount_all(s, &kinds, &walls, &[]).0
    }

    #[test]
    fn each_nightstand_gets_a_lamp_and_the_painting_hangs_above_the_bed() {
        let s = scene(&[
            ("bed-0", "double bed", [160.0, 210.0, 100.0]),
            ("nightstand-0", "nightstand", [50.0, 40.0, 55.0]),
            ("nightstand-1", "nightstand", [50.0, 40.0, 55.0]),
            ("lamp-0", "table lamp", [30.0, 30.0, 50.0]),
            ("lamp-1", "table lamp", [30.0, 30.0, 50.0]),
            ("painting-0", "framed painting", [100.0, 4.0, 70.0]),
            ("clock-0", "wall clock", [35.0, 5.0, 35.0]),
            ("floor-lamp-0", "lamp", [40.0, 40.0, 160.0]),
        ]);
        let m = mounted(&s);
        let mut ons: Vec<Option<Mounted>> = vec![m[3], m[4]];
        ons.sort_by_key(|x| format!("{x:?}"));
        assert_eq!(ons, vec![Some(Mounted::On(1)), Some(Mounted::On(2))]);
        assert_eq!(
            m[5],
            Some(Mounted::Wall {
                above: Some(0),
                across: None
            })
        );
        assert_eq!(
            m[6],
            Some(Mounted::Wall {
                above: None,
                across: None
            })
        );
        assert_eq!(m[7], None, "a 160 cm lamp stands on the floor");
        assert_eq!(m[0], None);
    }

    #[test]
    fn a_tv_takes_its_stand_and_without_one_the_wall_across_from_the_sofa() {
        let with = scene(&[
            ("sofa-0", "sofa", [200.0, 90.0, 85.0]),
            ("tv-stand-0", "tv stand", [150.0, 40.0, 50.0]),
            ("tv-0", "flat-screen tv", [120.0, 8.0, 70.0]),
        ]);
        assert_eq!(mounted(&with)[2], Some(Mounted::On(1)));
        let without = scene(&[
            ("sofa-0", "sofa", [200.0, 90.0, 85.0]),
            ("tv-0", "tv", [120.0, 8.0, 70.0]),
        ]);
        assert_eq!(
            mounted(&without)[1],
            Some(Mounted::Wall {
                above: None,
                across: Some(0)
            })
        );
    }

    #[test]
    fn a_full_top_sends_the_rest_elsewhere_and_a_user_saying_floor_is_obeyed() {
        let mut s = scene(&[
            ("side-table-0", "side table", [45.0, 45.0, 55.0]),
            ("lamp-0", "table lamp", [35.0, 35.0, 50.0]),
            ("vase-0", "vase", [30.0, 30.0, 40.0]),
            ("lamp-1", "table lamp", [30.0, 30.0, 50.0]),
        ]);
        s.assets[3].support = Some(Support::Floor);
        let m = mounted(&s);
        assert_eq!(m[1], Some(Mounted::On(0)));
        assert_eq!(m[2], None, "no room left on the side table");
        assert_eq!(m[3], None);
    }
}
