//! The planner's output: per-object constraints in the paper's vocabulary and ordered groups.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A positional relation between an object and a target object (the paper's six types).
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
}

impl Relation {
    /// Every relation, in a fixed order.
    pub const ALL: [Relation; 6] = [
        Relation::Near,
        Relation::SideOf,
        Relation::InFrontOf,
        Relation::AlignedWith,
        Relation::Opposite,
        Relation::Around,
    ];

    /// The canonical spelling used in files (`side_of`, `in_front_of`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Relation::Near => "near",
            Relation::SideOf => "side_of",
            Relation::InFrontOf => "in_front_of",
            Relation::AlignedWith => "aligned_with",
            Relation::Opposite => "opposite",
            Relation::Around => "around",
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
            _ => {
                return Err(format!(
                    "unknown relation {s:?}; expected one of near, side_of, in_front_of, aligned_with, opposite, around"
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
}

impl Plan {
    /// True when the plan asks `name` to stand against a wall.
    pub fn wants_wall(&self, name: &str) -> bool {
        self.constraints.get(name).is_some_and(|c| c.against_wall)
    }

    /// The index of the group holding `name`, if any.
    pub fn group_of(&self, name: &str) -> Option<usize> {
        self.groups.iter().position(|g| g.iter().any(|n| n == name))
    }
}
