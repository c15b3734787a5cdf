//! What a room's outline and openings say about its parts, in the words people use for them:
//! zones (the main area, and the alcoves, nooks, bays and arms around it), wall roles (the wall
//! opposite the door, walls without windows, the entrance wall, left and right) and corners
//! ranked by their distance from the door.
//!
//! One analysis serves the rule agents (where a request puts a piece), the predicates (whether
//! a placement honours it), the renders and the model prompts (which name zones and walls).
//!
//! Zones come from the grid the outline's own vertex coordinates draw: the cells on the floor,
//! the largest rectangle of them is the main area, and each connected rest is a zone of its own.
//! That is exact for outlines with axis-aligned walls and a close cut for slanted ones.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::Room;

/// A zone smaller than this share of the main area is a recess (an alcove, nook or bay);
/// a larger one is a wing (an arm of an L, a leg of a T or U).
const RECESS_SHARE: f64 = 0.4;

/// Cosine above which two directions count as the same (within about 37°).
const SAME_WAY: f64 = 0.8;

/// Zones thinner than this (cm) are slivers of a slanted wall, not places.
const MIN_ZONE_CM: f64 = 60.0;

/// What kind of part of the room a zone is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ZoneKind {
    /// The largest open rectangle of the floor.
    Main,
    /// A small part off the main area: an alcove, a nook, a bay.
    Recess,
    /// A large part off the main area: an arm of an L, a leg of a T or U.
    Wing,
}

/// A named part of the floor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Zone {
    /// `main`, `recess-1`, `wing-1`, ... (numbered by size, largest first).
    pub name: String,
    /// What kind of part it is.
    pub kind: ZoneKind,
    /// Its bounding box on the floor: lower-left and upper-right corners (cm).
    pub min: [f64; 2],
    /// Upper-right corner (cm).
    pub max: [f64; 2],
    /// Its floor area (cm²).
    pub area: f64,
    /// Walls (indices) bounding it.
    pub walls: Vec<usize>,
    /// Whether a window opens onto it.
    pub has_window: bool,
}

impl Zone {
    /// Whether `p` lies in the zone's box, `slack` cm around it allowed.
    pub fn contains(&self, p: DVec2, slack: f64) -> bool {
        p.x >= self.min[0] - slack
            && p.x <= self.max[0] + slack
            && p.y >= self.min[1] - slack
            && p.y <= self.max[1] + slack
    }

    /// How far (cm) `p` lies outside the zone's box (0 inside).
    pub fn distance(&self, p: DVec2) -> f64 {
        let dx = (self.min[0] - p.x).max(p.x - self.max[0]).max(0.0);
        let dy = (self.min[1] - p.y).max(p.y - self.max[1]).max(0.0);
        dx.hypot(dy)
    }

    /// The zone's centre.
    pub fn centre(&self) -> DVec2 {
        DVec2::new(
            (self.min[0] + self.max[0]) / 2.0,
            (self.min[1] + self.max[1]) / 2.0,
        )
    }
}

/// The roles one wall plays.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct WallRoles {
    /// The wall's index (the outline edge from vertex `index` to the next).
    pub index: usize,
    /// Its length (cm).
    pub length: f64,
    /// A door opens in it.
    pub has_door: bool,
    /// A window opens in it.
    pub has_window: bool,
    /// It is the wall of the main door.
    pub entrance: bool,
    /// It is the wall across the room from the main door (the farthest wall facing it).
    pub opposite_door: bool,
    /// It is the wall across the room from the main window (the widest; the farthest wall
    /// facing it): "the wall opposite the windows", "opposite the bay".
    #[serde(default)]
    pub opposite_window: bool,
    /// Seen from the main door looking in: `left`, `right`, `back` or `entrance`; `None` when
    /// the room has no door.
    pub from_door: Option<String>,
    /// Seen on the plan (x right, y up): `left`, `right`, `top` or `bottom`, by which way the
    /// wall faces; `None` for a wall at about 45°.
    pub on_plan: Option<String>,
    /// It runs at a slant (more than [`SLANT_DEG`] off the plan's axes), even when it still
    /// faces mostly one way ("the slanted wall" of a trapezoid room).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub slanted: bool,
}

/// Degrees off the plan's axes beyond which a wall counts as slanted.
pub const SLANT_DEG: f64 = 3.0;

/// A corner of the floor where two walls meet inside the room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Corner {
    /// The outline vertex.
    pub vertex: usize,
    /// Its position (cm).
    pub at: [f64; 2],
    /// Straight distance (cm) from the main door's centre (0 without doors).
    pub from_door: f64,
}

/// Zones, wall roles and corners of one room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RoomAnalysis {
    /// The main area first, then the other zones, largest first.
    pub zones: Vec<Zone>,
    /// One entry per wall, in outline order.
    pub walls: Vec<WallRoles>,
    /// The room's inner corners (walls meeting at less than 180° seen from inside), farthest
    /// from the main door first.
    pub corners: Vec<Corner>,
    /// The main door (the widest; the first of equals), if any.
    pub main_door: Option<usize>,
}

impl RoomAnalysis {
    /// The zones other than the main area.
    pub fn side_zones(&self) -> impl Iterator<Item = &Zone> {
        self.zones.iter().filter(|z| z.kind != ZoneKind::Main)
    }

    /// The zone named `name`.
    pub fn zone(&self, name: &str) -> Option<&Zone> {
        self.zones.iter().find(|z| z.name == name)
    }

    /// The corner "farthest from the door" a place means: the first of [`Self::corners`] (the
    /// farthest from the main door) lying in the zone the place also names, if it names one and
    /// one does ("the far corner of the main area" in an L whose farthest corner ends its arm);
    /// else the room's farthest.
    pub fn far_corner(&self, zone: Option<&str>) -> Option<&Corner> {
        let in_zone = |c: &&Corner| {
            zone.is_none_or(|z| {
                self.zones_named(z)
                    .iter()
                    .any(|zone| zone.contains(DVec2::new(c.at[0], c.at[1]), 1.0))
            })
        };
        self.corners
            .iter()
            .find(in_zone)
            .or_else(|| self.corners.first())
    }

    /// The zones a request's word means: a kind (`recess`, `wing`, `main`; a recess asked in a
    /// room without one is its side wing, and the other way round), a kind on a side of the
    /// plan (`wing-left`, `recess-top`: of that kind's zones, the one farthest that way from the
    /// main area's centre; all of them when none lies that way) or a zone's own name.
    pub fn zones_named(&self, asked: &str) -> Vec<&Zone> {
        if let Some((kind, side)) = asked.split_once('-')
            && let Some(way) = plan_side(side)
        {
            let all = self.zones_named(kind);
            let from = self.zones.first().map_or(DVec2::ZERO, Zone::centre);
            let reach = |z: &Zone| (z.centre() - from).dot(way);
            return match all
                .iter()
                .copied()
                .filter(|z| reach(z) > 1.0)
                .max_by(|a, b| reach(a).total_cmp(&reach(b)))
            {
                Some(z) => vec![z],
                None => all,
            };
        }
        let has = |k: ZoneKind| self.zones.iter().any(|z| z.kind == k);
        self.zones
            .iter()
            .filter(|z| match asked {
                "main" => z.kind == ZoneKind::Main,
                "recess" if has(ZoneKind::Recess) => z.kind == ZoneKind::Recess,
                "wing" if has(ZoneKind::Wing) => z.kind == ZoneKind::Wing,
                "recess" | "wing" => z.kind != ZoneKind::Main,
                name => z.name == name,
            })
            .collect()
    }

    /// The walls (indices) that play `role`.
    pub fn walls_with(&self, role: WallRole) -> Vec<usize> {
        let solid: Vec<&WallRoles> = self
            .walls
            .iter()
            .filter(|w| !w.has_door && !w.has_window)
            .collect();
        let longest_solid = solid.iter().map(|w| w.length).fold(0.0, f64::max);
        self.walls
            .iter()
            .filter(|w| match role {
                WallRole::OppositeDoor => w.opposite_door,
                WallRole::OppositeWindow => w.opposite_window,
                WallRole::Entrance => w.entrance,
                WallRole::NoWindow => !w.has_window && !w.has_door,
                WallRole::WithWindow => w.has_window,
                WallRole::LongestSolid => {
                    !w.has_door && !w.has_window && w.length >= longest_solid - 1e-6
                }
                WallRole::Left => w.on_plan.as_deref() == Some("left"),
                WallRole::Right => w.on_plan.as_deref() == Some("right"),
                WallRole::Top => w.on_plan.as_deref() == Some("top"),
                WallRole::Bottom => w.on_plan.as_deref() == Some("bottom"),
                WallRole::LeftFromDoor => w.from_door.as_deref() == Some("left"),
                WallRole::RightFromDoor => w.from_door.as_deref() == Some("right"),
                WallRole::Slanted => w.slanted,
            })
            .map(|w| w.index)
            .collect()
    }

    /// One line per zone and per wall, for prompts and reports.
    pub fn describe(&self) -> Vec<String> {
        let mut out = Vec::new();
        for z in &self.zones {
            let kind = match z.kind {
                ZoneKind::Main => "the main area",
                ZoneKind::Recess => "a recess (alcove, nook or bay)",
                ZoneKind::Wing => "a wing (an arm of the room)",
            };
            out.push(format!(
                "zone {}: {kind}, x {:.0}..{:.0}, y {:.0}..{:.0}, {:.1} m²{}",
                z.name,
                z.min[0],
                z.max[0],
                z.min[1],
                z.max[1],
                z.area / 10_000.0,
                if z.has_window { ", with a window" } else { "" }
            ));
        }
        for w in &self.walls {
            let mut roles = Vec::new();
            if w.entrance {
                roles.push("the entrance wall".to_string());
            }
            if w.opposite_door {
                roles.push("opposite the door".to_string());
            }
            if w.opposite_window {
                roles.push("opposite the main window".to_string());
            }
            if let Some(side) = w
                .from_door
                .as_deref()
                .filter(|s| *s == "left" || *s == "right")
            {
                roles.push(format!("on the {side} seen from the door"));
            }
            if let Some(side) = &w.on_plan {
                roles.push(format!("the {side} wall on the plan"));
            }
            if w.slanted {
                roles.push("slanted".to_string());
            }
            roles.push(match (w.has_door, w.has_window) {
                (false, false) => "solid (no door or window)".to_string(),
                (true, true) => "with a door and a window".to_string(),
                (true, false) => "with a door".to_string(),
                (false, true) => "with a window".to_string(),
            });
            out.push(format!(
                "wall {} ({:.0} cm): {}",
                w.index,
                w.length,
                roles.join(", ")
            ));
        }
        out
    }
}

/// A wall named by the part it plays, as requests name walls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WallRole {
    /// Across the room from the main door.
    OppositeDoor,
    /// Across the room from the main (widest) window.
    OppositeWindow,
    /// The wall of the main door ("by the entrance" pieces stand on it or next to it).
    Entrance,
    /// A wall without windows or doors.
    NoWindow,
    /// A wall with a window.
    WithWindow,
    /// The longest wall without openings.
    LongestSolid,
    /// The left wall on the plan (facing +x).
    Left,
    /// The right wall on the plan (facing -x).
    Right,
    /// The top wall on the plan (facing -y).
    Top,
    /// The bottom wall on the plan (facing +y).
    Bottom,
    /// On the left seen from the main door, looking in.
    LeftFromDoor,
    /// On the right seen from the main door, looking in.
    RightFromDoor,
    /// A wall at a slant on the plan (neither horizontal nor vertical).
    Slanted,
}

impl WallRole {
    /// The words for the role.
    pub fn words(self) -> &'static str {
        match self {
            WallRole::OppositeDoor => "the wall opposite the door",
            WallRole::OppositeWindow => "the wall opposite the main window",
            WallRole::Entrance => "the entrance wall",
            WallRole::NoWindow => "a wall without windows",
            WallRole::WithWindow => "a wall with a window",
            WallRole::LongestSolid => "the longest solid wall",
            WallRole::Left => "the left wall",
            WallRole::Right => "the right wall",
            WallRole::Top => "the top wall",
            WallRole::Bottom => "the bottom wall",
            WallRole::LeftFromDoor => "the wall on the left as you enter",
            WallRole::RightFromDoor => "the wall on the right as you enter",
            WallRole::Slanted => "the slanted wall",
        }
    }
}

impl Room {
    /// The room's zones, wall roles and corners.
    pub fn analysis(&self) -> RoomAnalysis {
        let outline = self.outline();
        let edges = self.walls();
        let main_door = (0..self.doors.len()).max_by(|&a, &b| {
            self.doors[a]
                .width
                .total_cmp(&self.doors[b].width)
                .then(b.cmp(&a))
        });
        let door_at = main_door.and_then(|i| {
            let d = &self.doors[i];
            let e = edges.get(d.wall)?;
            Some((e.point(d.at), e.inward_normal(), d.wall))
        });
        let zones = zones(self, &outline);
        let mut walls: Vec<WallRoles> = edges
            .iter()
            .map(|e| WallRoles {
                index: e.index,
                length: e.length(),
                has_door: self.doors.iter().any(|d| d.wall == e.index),
                has_window: self.windows.iter().any(|w| w.wall == e.index),
                entrance: door_at.is_some_and(|(_, _, w)| w == e.index),
                opposite_door: false,
                opposite_window: false,
                from_door: None,
                on_plan: on_plan(e.inward_normal()),
                slanted: {
                    let n = e.inward_normal();
                    n.x.abs().min(n.y.abs()) > SLANT_DEG.to_radians().sin()
                },
            })
            .collect();
        if let Some((p, n, _)) = door_at {
            let right = DVec2::new(n.y, -n.x);
            for (w, e) in walls.iter_mut().zip(&edges) {
                let m = e.inward_normal();
                w.from_door = Some(
                    if w.entrance {
                        "entrance"
                    } else if m.dot(n) < -SAME_WAY {
                        "back"
                    } else if m.dot(right) < -SAME_WAY {
                        "right"
                    } else if m.dot(right) > SAME_WAY {
                        "left"
                    } else {
                        "slanted"
                    }
                    .to_string(),
                );
            }
            if let Some(i) = opposite(&edges, p, n) {
                walls[i].opposite_door = true;
            }
        }
        let main_window = (0..self.windows.len()).max_by(|&a, &b| {
            self.windows[a]
                .width
                .total_cmp(&self.windows[b].width)
                .then(b.cmp(&a))
        });
        if let Some(w) = main_window.map(|i| &self.windows[i])
            && let Some(e) = edges.get(w.wall)
            && let Some(i) = opposite(&edges, e.point(w.at), e.inward_normal())
        {
            walls[i].opposite_window = true;
        }
        let mut corners: Vec<Corner> = (0..outline.len())
            .filter(|&i| {
                let n = outline.len();
                let (a, b, c) = (outline[(i + n - 1) % n], outline[i], outline[(i + 1) % n]);
                // Counter-clockwise outline: a left turn is a corner seen from inside.
                (b - a).perp_dot(c - b) > 1e-9
            })
            .map(|i| Corner {
                vertex: i,
                at: [outline[i].x, outline[i].y],
                from_door: door_at.map_or(0.0, |(p, _, _)| outline[i].distance(p)),
            })
            .collect();
        corners.sort_by(|a, b| b.from_door.total_cmp(&a.from_door));
        RoomAnalysis {
            zones,
            walls,
            corners,
            main_door,
        }
    }
}

/// The direction a side of the plan names: `left` is -x, `top` is +y.
fn plan_side(side: &str) -> Option<DVec2> {
    Some(match side {
        "left" => DVec2::NEG_X,
        "right" => DVec2::X,
        "top" => DVec2::Y,
        "bottom" => DVec2::NEG_Y,
        _ => return None,
    })
}

/// The wall across the room from a point `p` on a wall whose inward normal is `n`: of the walls
/// facing it, the one farthest into the room (its middle's depth from `p`), the longer one of
/// two at the same depth.
fn opposite(edges: &[super::Edge], p: DVec2, n: DVec2) -> Option<usize> {
    let depth = |e: &super::Edge| ((e.start + e.end) / 2.0 - p).dot(n);
    edges
        .iter()
        .filter(|e| e.inward_normal().dot(n) < -SAME_WAY)
        .max_by(|a, b| {
            (depth(a).round())
                .total_cmp(&depth(b).round())
                .then(a.length().total_cmp(&b.length()))
        })
        .map(|e| e.index)
}

/// `left`, `right`, `top` or `bottom`: which wall of the plan an inward normal belongs to.
fn on_plan(n: DVec2) -> Option<String> {
    let side = if n.x > SAME_WAY {
        "left"
    } else if n.x < -SAME_WAY {
        "right"
    } else if n.y > SAME_WAY {
        "bottom"
    } else if n.y < -SAME_WAY {
        "top"
    } else {
        return None;
    };
    Some(side.to_string())
}

/// The zones of the floor: the largest rectangle of grid cells, then each connected rest.
fn zones(room: &Room, outline: &[DVec2]) -> Vec<Zone> {
    let mut xs: Vec<f64> = outline.iter().map(|v| v.x).collect();
    let mut ys: Vec<f64> = outline.iter().map(|v| v.y).collect();
    for v in [&mut xs, &mut ys] {
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1.0);
    }
    let (nx, ny) = (xs.len().saturating_sub(1), ys.len().saturating_sub(1));
    let cell_area = |i: usize, j: usize| (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
    let inside: Vec<Vec<bool>> = (0..nx)
        .map(|i| {
            (0..ny)
                .map(|j| {
                    let c = DVec2::new((xs[i] + xs[i + 1]) / 2.0, (ys[j] + ys[j + 1]) / 2.0);
                    room.contains_point(c, 0.0)
                })
                .collect()
        })
        .collect();
    // The largest rectangle of floor cells: for each first column, widen one column at a time,
    // keep the rows whose cells are all floor so far, and take the longest run of such rows.
    // O(columns² · rows), fast for the largest outlines validation lets through.
    let mut best = (0.0, 0, 0, 0, 0);
    for i0 in 0..nx {
        let mut rows_ok = vec![true; ny];
        for i1 in i0..nx {
            for (j, ok) in rows_ok.iter_mut().enumerate() {
                *ok &= inside[i1][j];
            }
            if !rows_ok.iter().any(|ok| *ok) {
                break;
            }
            let width = xs[i1 + 1] - xs[i0];
            let mut j0 = 0;
            for j in 0..=ny {
                if j < ny && rows_ok[j] {
                    continue;
                }
                if j > j0 {
                    let area = width * (ys[j] - ys[j0]);
                    if area > best.0 {
                        best = (area, i0, i1, j0, j - 1);
                    }
                }
                j0 = j + 1;
            }
        }
    }
    let (main_area, i0, i1, j0, j1) = best;
    let mut taken: Vec<Vec<bool>> = (0..nx)
        .map(|i| {
            (0..ny)
                .map(|j| !inside[i][j] || (i0..=i1).contains(&i) && (j0..=j1).contains(&j))
                .collect()
        })
        .collect();
    let mut zones = vec![make_zone(
        room,
        "main".into(),
        ZoneKind::Main,
        [xs[i0], ys[j0]],
        [xs[i1 + 1], ys[j1 + 1]],
        main_area,
    )];
    let mut rest = Vec::new();
    for si in 0..nx {
        for sj in 0..ny {
            if taken[si][sj] {
                continue;
            }
            // One connected rest, by flood fill over neighbouring cells.
            let (mut min, mut max, mut area) = ([f64::MAX; 2], [f64::MIN; 2], 0.0);
            let mut stack = vec![(si, sj)];
            taken[si][sj] = true;
            while let Some((i, j)) = stack.pop() {
                area += cell_area(i, j);
                min = [min[0].min(xs[i]), min[1].min(ys[j])];
                max = [max[0].max(xs[i + 1]), max[1].max(ys[j + 1])];
                let near = [
                    (i.wrapping_sub(1), j),
                    (i + 1, j),
                    (i, j.wrapping_sub(1)),
                    (i, j + 1),
                ];
                for (a, b) in near {
                    if a < nx && b < ny && !taken[a][b] {
                        taken[a][b] = true;
                        stack.push((a, b));
                    }
                }
            }
            if max[0] - min[0] >= MIN_ZONE_CM && max[1] - min[1] >= MIN_ZONE_CM {
                rest.push((area, min, max));
            }
        }
    }
    rest.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (mut recesses, mut wings) = (0, 0);
    for (area, min, max) in rest {
        let (kind, name) = if area < RECESS_SHARE * main_area {
            recesses += 1;
            (ZoneKind::Recess, format!("recess-{recesses}"))
        } else {
            wings += 1;
            (ZoneKind::Wing, format!("wing-{wings}"))
        };
        zones.push(make_zone(room, name, kind, min, max, area));
    }
    zones
}

/// A zone with the walls that bound it and whether a window opens onto it.
fn make_zone(
    room: &Room,
    name: String,
    kind: ZoneKind,
    min: [f64; 2],
    max: [f64; 2],
    area: f64,
) -> Zone {
    let mut zone = Zone {
        name,
        kind,
        min,
        max,
        area,
        walls: Vec::new(),
        has_window: false,
    };
    for e in room.walls() {
        // A wall bounds the zone when its stretch inside the zone's box is long enough to
        // stand something on.
        let inside = (0..=20)
            .filter(|k| zone.contains(e.point(e.length() * *k as f64 / 20.0), 1.0))
            .count();
        if inside as f64 / 21.0 * e.length() >= MIN_ZONE_CM.min(e.length() * 0.5) && inside >= 2 {
            zone.walls.push(e.index);
        }
    }
    zone.has_window = room.windows.iter().any(|w| {
        room.walls()
            .get(w.wall)
            .is_some_and(|e| zone.contains(e.point(w.at), 1.0))
    });
    zone
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room::{Door, Window};

    fn window(wall: usize, at: f64) -> Window {
        Window {
            wall,
            at,
            width: 100.0,
            sill: 90.0,
            height: 120.0,
        }
    }

    /// An L: an 800 x 300 main part with a 350 x 300 arm on top of its left end.
    fn l_room() -> Room {
        let mut r = Room::from_polygon(vec![
            [0.0, 0.0],
            [800.0, 0.0],
            [800.0, 300.0],
            [350.0, 300.0],
            [350.0, 600.0],
            [0.0, 600.0],
        ]);
        r.doors = vec![Door::new(0, 450.0, 90.0)];
        r.windows = vec![window(4, 175.0)];
        r
    }

    #[test]
    fn an_l_has_a_main_area_and_a_wing() {
        let a = l_room().analysis();
        assert_eq!(a.zones.len(), 2, "{:?}", a.zones);
        assert_eq!(a.zones[0].kind, ZoneKind::Main);
        assert_eq!(a.zones[0].area, 800.0 * 300.0);
        let wing = &a.zones[1];
        assert_eq!(wing.kind, ZoneKind::Wing);
        assert_eq!((wing.min, wing.max), ([0.0, 300.0], [350.0, 600.0]));
        assert!(wing.has_window);
        assert!(wing.walls.contains(&4) && wing.walls.contains(&3));
    }

    #[test]
    fn a_small_alcove_is_a_recess() {
        let mut r = Room::from_polygon(vec![
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 100.0],
            [520.0, 100.0],
            [520.0, 250.0],
            [400.0, 250.0],
            [400.0, 350.0],
            [0.0, 350.0],
        ]);
        r.doors = vec![Door::new(0, 100.0, 90.0)];
        let a = r.analysis();
        let recess: Vec<&Zone> = a.side_zones().collect();
        assert_eq!(recess.len(), 1);
        assert_eq!(recess[0].kind, ZoneKind::Recess);
        assert_eq!(
            (recess[0].min, recess[0].max),
            ([400.0, 100.0], [520.0, 250.0])
        );
        // The alcove's end wall bounds it; the main room's far wall does not.
        assert!(recess[0].walls.contains(&3));
        assert!(!recess[0].walls.contains(&7));
    }

    #[test]
    fn a_steep_slant_is_slanted_and_still_a_side() {
        // A trapezoid whose right wall leans 11° from the vertical: slanted, and on the right.
        let r = Room::from_polygon(vec![[0.0, 0.0], [820.0, 0.0], [700.0, 640.0], [0.0, 640.0]]);
        let a = r.analysis();
        assert_eq!(a.walls_with(WallRole::Slanted), vec![1]);
        assert_eq!(a.walls_with(WallRole::Right), vec![1]);
        assert!(
            Room::rect(500.0, 400.0)
                .analysis()
                .walls_with(WallRole::Slanted)
                .is_empty()
        );
    }

    #[test]
    fn the_wall_opposite_the_widest_window() {
        // Windows on the right (narrow) and the bottom (wide): the top wall is opposite the
        // main window.
        let mut r = Room::rect(500.0, 400.0);
        let mut wide = window(0, 250.0);
        wide.width = 200.0;
        r.windows = vec![window(1, 200.0), wide];
        let a = r.analysis();
        assert_eq!(a.walls_with(WallRole::OppositeWindow), vec![2]);
        assert!(
            Room::rect(500.0, 400.0)
                .analysis()
                .walls_with(WallRole::OppositeWindow)
                .is_empty()
        );
    }

    #[test]
    fn a_wing_is_named_by_its_side_of_the_plan() {
        // A U: a bottom bar with two legs going up, a core between them.
        let r = Room::from_polygon(vec![
            [0.0, 0.0],
            [900.0, 0.0],
            [900.0, 600.0],
            [620.0, 600.0],
            [620.0, 300.0],
            [280.0, 300.0],
            [280.0, 600.0],
            [0.0, 600.0],
        ]);
        let a = r.analysis();
        assert_eq!(a.zones_named("wing").len(), 2, "{:?}", a.zones);
        let left = a.zones_named("wing-left");
        let right = a.zones_named("wing-right");
        assert_eq!((left.len(), right.len()), (1, 1), "{:?}", a.zones);
        assert_eq!((left[0].min[0], right[0].max[0]), (0.0, 900.0));
        // No wing lies below the main area: "the bottom wing" is any wing.
        assert_eq!(a.zones_named("wing-bottom").len(), 2);
        // A zone's own name is still its name.
        assert_eq!(a.zones_named(&left[0].name).len(), 1);
    }

    #[test]
    fn wall_roles_from_the_door() {
        // A rectangle with the door on the bottom wall: the top wall is opposite it; looking in
        // (up), the right wall is on the right.
        let mut r = Room::rect(500.0, 400.0);
        r.doors = vec![Door::new(0, 100.0, 90.0)];
        r.windows = vec![window(1, 200.0)];
        let a = r.analysis();
        assert_eq!(a.walls_with(WallRole::OppositeDoor), vec![2]);
        assert_eq!(a.walls_with(WallRole::Entrance), vec![0]);
        assert_eq!(a.walls_with(WallRole::RightFromDoor), vec![1]);
        assert_eq!(a.walls_with(WallRole::LeftFromDoor), vec![3]);
        assert_eq!(a.walls_with(WallRole::NoWindow), vec![2, 3]);
        assert_eq!(a.walls_with(WallRole::Left), vec![3]);
        assert_eq!(a.walls_with(WallRole::Top), vec![2]);
        // The farthest corners from a door near the bottom-left are the top-right one first.
        assert_eq!(a.corners[0].at, [500.0, 400.0]);
        assert_eq!(a.corners.len(), 4);
    }

    #[test]
    fn the_opposite_wall_is_the_farthest_facing_the_door() {
        // The L's door is on the bottom wall: of the walls facing down, the arm's top (y 600)
        // is farther than the main part's top (y 300).
        let a = l_room().analysis();
        assert_eq!(a.walls_with(WallRole::OppositeDoor), vec![4]);
        // Reflex vertex 3 (the inner corner) is no corner.
        assert!(a.corners.iter().all(|c| c.vertex != 3));
        assert_eq!(a.corners.len(), 5);
    }

    #[test]
    fn a_room_without_doors_has_no_door_roles() {
        let a = Room::rect(300.0, 300.0).analysis();
        assert!(a.main_door.is_none());
        assert!(a.walls_with(WallRole::OppositeDoor).is_empty());
        assert_eq!(a.zones.len(), 1);
        assert!(a.describe().iter().any(|l| l.starts_with("zone main")));
    }

    #[test]
    fn a_round_room_of_many_vertices_has_its_main_area_inside() {
        // 256 vertices, the most validation lets through: the main area is a rectangle of floor
        // inside the circle, at least half of it (an inscribed square is 2/pi of the disc).
        let points: Vec<[f64; 2]> = (0..256)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 256.0;
                [300.0 + 300.0 * t.cos(), 300.0 + 300.0 * t.sin()]
            })
            .collect();
        let room = Room::from_polygon(points);
        let a = room.analysis();
        let main = &a.zones[0];
        assert_eq!(main.kind, ZoneKind::Main);
        assert!(
            main.area >= 0.5 * room.area(),
            "{} of {}",
            main.area,
            room.area()
        );
        // Cells count as floor by their centre, so on a curve the box may reach a few cm out.
        for corner in [
            main.min,
            main.max,
            [main.min[0], main.max[1]],
            [main.max[0], main.min[1]],
        ] {
            assert!(room.contains_point(DVec2::from(corner), 10.0), "{corner:?}");
        }
    }
}
