//! Trials on a [`ReachMap`]: objects added after [`ReachMap::begin_trial`] are taken back by
//! [`ReachMap::roll_back`], which restores the map as it was, cell for cell. A designer trying
//! several arrangements on the same floor so needs no copy of the map per try (a copy of a big
//! hall's raster costs megabytes).

use super::{ReachMap, reach_zone};

/// What the objects added since a trial began changed, so it can be undone.
#[derive(Debug, Clone, Default)]
pub(super) struct Journal {
    /// Each changed cell's former (free, label), in the order of change.
    cells: Vec<(usize, bool, u32)>,
    /// Each changed region size's former (label, size), in the order of change.
    sizes: Vec<(usize, usize)>,
    /// How many regions there were.
    regions: usize,
    /// How many objects there were.
    objects: usize,
    /// Objects, of those, that were reached and are reached no longer.
    lost: Vec<usize>,
    /// How many objects were unreachable.
    unreachable: usize,
    /// The largest region's label.
    largest: u32,
    /// The map as it was before an added object made it start afresh (with its own journal of
    /// what came before): rolling back returns to it first.
    before_rebuild: Option<Box<ReachMap>>,
}

impl Journal {
    /// The journal of a trial beginning on `map`.
    fn starting(map: &ReachMap) -> Self {
        Journal {
            regions: map.sizes.len(),
            objects: map.objects.len(),
            unreachable: map.unreachable,
            largest: map.largest,
            ..Journal::default()
        }
    }

    /// Notes that cell `k` is about to change from `free`, `label`.
    pub(super) fn cell(&mut self, k: usize, free: bool, label: u32) {
        self.cells.push((k, free, label));
    }

    /// Notes that region `label`'s size is about to change from `size`.
    pub(super) fn size(&mut self, label: usize, size: usize) {
        self.sizes.push((label, size));
    }

    /// Notes that object `i`, reached so far, is reached no longer.
    pub(super) fn lost(&mut self, i: usize) {
        self.lost.push(i);
    }
}

impl ReachMap {
    /// Begins a trial: what is added from now on can be taken back by
    /// [`roll_back`](Self::roll_back). A trial already under way starts over from here.
    pub fn begin_trial(&mut self) {
        self.journal = Some(Box::new(Journal::starting(self)));
    }

    /// Takes back every object added since [`begin_trial`](Self::begin_trial) and ends the
    /// trial; the map counts as it did then. Without a trial, nothing changes.
    pub fn roll_back(&mut self) {
        let Some(mut journal) = self.journal.take() else {
            return;
        };
        if let Some(before) = journal.before_rebuild.take() {
            *self = *before;
            self.roll_back();
            return;
        }
        for &(k, free, label) in journal.cells.iter().rev() {
            self.free[k] = free;
            self.label[k] = label;
        }
        for &(l, size) in journal.sizes.iter().rev() {
            self.sizes[l] = size;
        }
        self.sizes.truncate(journal.regions);
        self.walkable.truncate(journal.regions);
        while self.objects.len() > journal.objects {
            if let Some(r) = self.objects.pop() {
                self.zones.remove_last(&reach_zone(&r.footprint));
            }
        }
        for &i in journal.lost.iter().filter(|&&i| i < journal.objects) {
            self.objects[i].reached = true;
        }
        self.unreachable = journal.unreachable;
        self.largest = journal.largest;
    }

    /// Whether a trial is under way.
    pub(super) fn in_trial(&self) -> bool {
        self.journal.is_some()
    }

    /// Replaces the map by `fresh` (made afresh after an added object), keeping the map it
    /// replaces for the trial under way to return to.
    pub(super) fn replace_in_trial(&mut self, fresh: ReachMap) {
        let before = std::mem::replace(self, fresh);
        if before.in_trial() {
            let mut journal = Journal::starting(self);
            journal.before_rebuild = Some(Box::new(before));
            self.journal = Some(Box::new(journal));
        }
    }
}
