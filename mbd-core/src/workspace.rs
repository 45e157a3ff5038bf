//! Caller-owned scratch of a model's hot methods (the faer `*_scratch` / `MemStack` style,
//! object-safe).
//!
//! The hot methods of [`SecondOrderSystem`](crate::SecondOrderSystem) —
//! [`forces`](crate::SecondOrderSystem::forces),
//! [`force_tangent`](crate::SecondOrderSystem::force_tangent) and
//! [`dynamic_residual`](crate::SecondOrderSystem::dynamic_residual) — take `&self` (models are
//! shared, e.g. as `&dyn SecondOrderSystem` in a [`CompositeSystem`](crate::CompositeSystem))
//! and a `&mut Workspace` owned by the caller: the stepper, the Newton problem or the study
//! keeps one per model for as long as it runs. A model that needs work buffers (element
//! contact, local matrices) or a cache between calls (a reused tangent) keeps them in its own
//! private type `T` and gets it with [`Workspace::get_or_insert_with`], which creates it
//! lazily on the first call and hands back the same value afterwards; a model without scratch
//! ignores the argument. No model holds hidden interior-mutable scratch (`Mutex`, `RefCell`).
//!
//! One workspace serves one model instance at a time: the type erasure keys the content by
//! its type only, so a model whose scratch depends on its sizes checks them (or keys a cache
//! by the coordinates it was evaluated at) before reusing it. A composite gives each part its
//! own workspace ([`Workspace::parts`]).

use std::any::Any;

/// Type-erased scratch of one model, owned by the caller of its hot methods (see the module
/// documentation). Cheap to create: it allocates nothing until a model asks for its scratch.
#[derive(Default)]
pub struct Workspace {
    slot: Option<Box<dyn Any + Send>>,
}

impl std::fmt::Debug for Workspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Workspace")
            .field("filled", &self.slot.is_some())
            .finish()
    }
}

impl Workspace {
    /// An empty workspace.
    pub fn new() -> Self {
        Self::default()
    }

    /// The model's scratch of type `T`, created by `init` if the workspace is empty or holds
    /// another type (then the old content is dropped).
    pub fn get_or_insert_with<T: Any + Send>(&mut self, init: impl FnOnce() -> T) -> &mut T {
        if !self.slot.as_ref().is_some_and(|b| b.is::<T>()) {
            self.slot = Some(Box::new(init()));
        }
        match self.slot.as_mut().and_then(|b| b.downcast_mut::<T>()) {
            Some(t) => t,
            None => unreachable!("the slot holds a T: it was just checked or filled"),
        }
    }

    /// The model's scratch of type `T`, if the workspace holds one (e.g. to read statistics
    /// a model keeps there).
    pub fn get<T: Any + Send>(&self) -> Option<&T> {
        self.slot.as_ref().and_then(|b| b.downcast_ref::<T>())
    }

    /// `n` workspaces, one per part of a composite model (kept in this workspace).
    pub fn parts(&mut self, n: usize) -> &mut [Workspace] {
        let parts = self.get_or_insert_with(Vec::<Workspace>::new);
        parts.resize_with(n, Workspace::new);
        parts
    }

    /// Empties the workspace (the next call of a model creates its scratch anew).
    pub fn clear(&mut self) {
        self.slot = None;
    }
}

#[cfg(test)]
mod tests {
    use super::Workspace;

    // invariant: the same value comes back until the type changes
    #[test]
    fn keeps_value_per_type() {
        let mut ws = Workspace::new();
        *ws.get_or_insert_with(|| 1_u32) += 1;
        assert_eq!(*ws.get_or_insert_with(|| 10_u32), 2);
        assert_eq!(ws.get::<u64>(), None);
        assert_eq!(*ws.get_or_insert_with(|| 7_u64), 7);
        assert_eq!(ws.get::<u32>(), None);
        assert_eq!(ws.parts(3).len(), 3);
        ws.parts(3)[1].get_or_insert_with(|| 5_i8);
        assert_eq!(ws.parts(3)[1].get::<i8>(), Some(&5));
    }
}
