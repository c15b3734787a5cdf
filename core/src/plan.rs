//! The planner's output: per-object constraints in the paper's vocabulary and ordered groups.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

pub use crate::room::analysis::WallRole;

/// A positional relation between an object and a target object: the paper's six types, and the
/// two of objects off the floor (`on` another object's top, hung `above` a floor piece).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Relation {
    /// Within a short gap of the target.
    Near,
    /// Beside the target, to its left or right.
    SideOf,
    /// In the target's front zone.
    InFrontOf,
    /// Lined up with the target.
    AlignedWith,
    /// Across from the target, the two facing each other.
    Opposite,
    /// Close to the target and turned towards it (chairs around a table).
    Around,
    /// Standing on the target's top (a lamp on a nightstand); the plan's `support` is `surface`.
    On,
    /// Hanging on the wall behind the target, centred over it (a painting above the sofa); the
    /// plan's `support` is `wall`.
    Above,
    /// Back to back with the target, the two facing away from each other (two rows of desks in
    /// a pod, a sofa backing onto a console or another sofa).
    BackToBack,
}

impl Relation {
    /// Every relation, in a fixed order.
    pub const ALL: [Relation; 9] = [
        Relation::Near,
        Relation::SideOf,
        Relation::InFrontOf,
        Relation::AlignedWith,
        Relation::Opposite,
        Relation::Around,
        Relation::On,
        Relation::Above,
        Relation::BackToBack,
    ];

    /// The paper's six relations between objects on the floor (what the model prompts list when
    /// nothing in the scene leaves the floor).
    pub const ON_FLOOR: [Relation; 6] = [
        Relation::Near,
        Relation::SideOf,
        Relation::InFrontOf,
        Relation::AlignedWith,
        Relation::Opposite,
        Relation::Around,
    ];

    /// True for the relations of objects off the floor (`on`, `above`).
    pub fn off_floor(self) -> bool {
        matches!(self, Relation::On | Relation::Above)
    }

    /// The canonical spelling used in files (`side_of`, `in_front_of`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Relation::Near => "near",
            Relation::SideOf => "side_of",
            Relation::InFrontOf => "in_front_of",
            Relation::AlignedWith => "aligned_with",
            Relation::Opposite => "opposite",
            Relation::Around => "around",
            Relation::On => "on",
            Relation::Above => "above",
            Relation::BackToBack => "back_to_back",
        }
    }

    /// The words a person (or a prompt) would use: `side of`, `in front of`, ...
    pub fn words(self) -> &'static str {
        match self {
            Relation::Near => "near",
            Relation::SideOf => "beside",
            Relation::InFrontOf => "in front of",
            Relation::AlignedWith => "aligned with",
            Relation::Opposite => "opposite",
            Relation::Around => "around",
            Relation::On => "on top of",
            Relation::Above => "hung above",
            Relation::BackToBack => "back to back with",
        }
    }
}

impl fmt::Display for Relation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for Relation {
    type Err = String;

    /// Accepts `side_of`, `side of`, `Side-Of`, `beside`, `in front of`, ... (case and separators ignored).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let key: String = s
            .trim()
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric())
            .collect();
        Ok(match key.as_str() {
            "near" | "nextto" | "close" | "closeto" => Relation::Near,
            "sideof" | "beside" | "besides" | "side" => Relation::SideOf,
            "infrontof" | "front" | "infront" => Relation::InFrontOf,
            "alignedwith" | "aligned" | "alignwith" => Relation::AlignedWith,
            "opposite" | "oppositeof" | "opposite_to" | "oppositeto" | "facingeachother" => {
                Relation::Opposite
            }
            "around" | "surrounding" => Relation::Around,
            "on" | "ontopof" | "ontop" | "upon" => Relation::On,
            "above" | "over" | "hungabove" | "hangingabove" => Relation::Above,
            "backtoback" | "backtobackwith" | "backtobackof" => Relation::BackToBack,
            _ => {
                return Err(format!(
                    "unknown relation {s:?}; expected one of near, side_of, in_front_of, aligned_with, opposite, around, on, above, back_to_back"
                ));
            }
        })
    }
}

impl Serialize for Relation {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl<'de> Deserialize<'de> for Relation {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// On the wire a relation is its canonical spelling (`side_of`, ...).
impl schemars::JsonSchema for Relation {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Relation".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names: Vec<&str> = Relation::ALL.iter().map(|r| r.as_str()).collect();
        schemars::json_schema!({
            "description": "A positional relation to the target object.",
            "type": "string",
            "enum": names,
        })
    }
}

/// One positional relation of an object to a target.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RelationSpec {
    /// The relation type.
    pub relation: Relation,
    /// The target object's name.
    pub target: String,
}

/// What the plan asks of one object: the paper's `c_wall`, `c_rel` and `c_rot`.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObjectConstraints {
    /// The object's back must lie on a wall with its front towards the room.
    #[serde(default)]
    pub against_wall: bool,
    /// Positional relations to other objects.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub relations: Vec<RelationSpec>,
    /// The object this one should face.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub facing: Option<String>,
    /// Where in the room it should stand, by the room's own parts (a zone, a wall's role, the
    /// far corner, under a window, by the entrance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub place: Option<Place>,
    /// Where it goes when not on the floor: `surface` (on the top of its `on` relation's
    /// target) or `wall` (hung on a wall, above its `above` relation's target if it has one).
    /// Absent: on the floor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub support: Option<crate::scene::Support>,
}

/// Where in the room an object is asked to stand, in the words of the room's analysis
/// ([`crate::room::analysis`]): every part that is given must hold.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Place {
    /// A zone: `recess` (an alcove, nook or bay), `wing` (an arm of an L, T or U), `main`, or
    /// a zone's own name (`recess-1`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zone: Option<String>,
    /// A wall by its role: its back on such a wall.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall: Option<WallRole>,
    /// In the corner farthest from the main door.
    #[serde(default, skip_serializing_if = "is_false")]
    pub far_corner: bool,
    /// Under a window: back on the window's wall, across the window's span.
    #[serde(default, skip_serializing_if = "is_false")]
    pub under_window: bool,
    /// By the main door, clear of its swing.
    #[serde(default, skip_serializing_if = "is_false")]
    pub by_entrance: bool,
}

fn is_false(b: &bool) -> bool {
    !b
}

impl Place {
    /// True when nothing is asked.
    pub fn is_empty(&self) -> bool {
        *self == Place::default()
    }
}

impl fmt::Display for Place {
    /// The request in words: `in a recess, on the wall opposite the door`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if let Some(z) = &self.zone {
            parts.push(match z.as_str() {
                "recess" => "in the alcove (recess)".to_string(),
                "wing" => "in the side wing".to_string(),
                "main" => "in the main area".to_string(),
                other => format!("in zone {other}"),
            });
        }
        if let Some(w) = self.wall {
            parts.push(format!("on {}", w.words()));
        }
        if self.far_corner {
            parts.push("in the corner farthest from the door".into());
        }
        if self.under_window {
            parts.push("under a window".into());
        }
        if self.by_entrance {
            parts.push("by the entrance".into());
        }
        f.write_str(&parts.join(", "))
    }
}

/// The planner's output: constraints per object and the ordered groups to place.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// Constraints keyed by object name.
    #[serde(default)]
    pub constraints: BTreeMap<String, ObjectConstraints>,
    /// Disjoint groups of object names, in placement order.
    #[serde(default)]
    pub groups: Vec<Vec<String>>,
    /// Members arranged together in a shape ("six chairs in a semicircle facing the piano"):
    /// the designer poses them as one, each member in its place of the shape.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub formations: Vec<Formation>,
}

/// The shape of a [`Formation`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FormationShape {
    /// Rows facing the focus (`count` rows); desks in rows face away from it, their chairs
    /// towards it.
    Rows,
    /// An arc (a semicircle) of seats around the focus, each turned to it.
    Arc,
    /// Seats evenly around the focus.
    Ring,
    /// Seats down each long side of the focus (a table), `count` per side.
    PerSide,
    /// Members along the focus's front (stools along an island).
    AlongFront,
    /// Pods of desks (`count` pods), each two rows back to back, each desk's chair at its
    /// front.
    Pods,
    /// One member in front of each object of `of` (a music stand in front of each chair).
    OnePerMember,
    /// One member behind each object of `of`, on its far side from what it faces, turned
    /// the same way (a stool behind each easel for its painter).
    BehindEach,
    /// Shelving in parallel lines (`count` lines) with aisles between them, every aisle with
    /// fronts on both sides, the block standing free of the walls (a shop's gondolas).
    Aisles,
    /// Tables in a U (a base and two arms), its open end towards the focus (a screen, a
    /// board) or, with none, towards the wall opposite the door; the seats round the outside
    /// of the U facing in, `count` per table (else shared out evenly). Members: the tables,
    /// then the seats.
    UTables,
    /// Two desks meeting in a corner of the room in an L, both backs on the walls, the chair
    /// in the crook: members the main desk, the return desk, then the chair.
    LDesks,
}

/// Objects arranged together in a shape, with counts.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Formation {
    /// The shape.
    pub shape: FormationShape,
    /// What the formation is arranged about (the piano of an arc, the board of rows, the
    /// table of seats); none for pods, which stand on their own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus: Option<String>,
    /// The members, in order.
    pub members: Vec<String>,
    /// Rows of `rows`, pods of `pods`, seats per side of `per_side`, lines of `aisles`, seats
    /// per table of `u_tables`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<usize>,
    /// For `one_per_member` and `behind_each`: the objects each member stands before (behind),
    /// in the members' order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub of: Vec<String>,
}

impl Plan {
    /// The formation `name` is a member of, if any.
    pub fn formation_of(&self, name: &str) -> Option<&Formation> {
        self.formations
            .iter()
            .find(|f| f.members.iter().any(|m| m == name))
    }
}

impl Plan {
    /// True when the plan asks `name` to stand against a wall.
    pub fn wants_wall(&self, name: &str) -> bool {
        self.constraints.get(name).is_some_and(|c| c.against_wall)
    }

    /// Where the plan puts `name` when it leaves the floor: `Some(Surface)` or `Some(Wall)`;
    /// `None` on the floor.
    pub fn support_of(&self, name: &str) -> Option<crate::scene::Support> {
        self.constraints
            .get(name)
            .and_then(|c| c.support)
            .filter(|s| *s != crate::scene::Support::Floor)
    }

    /// The index of the group holding `name`, if any.
    pub fn group_of(&self, name: &str) -> Option<usize> {
        self.groups.iter().position(|g| g.iter().any(|n| n == name))
    }
}
