//! # ancf
//!
//! Absolute nodal coordinate formulation elements (Kerkkänen 2006): the 2D shear-deformable
//! linear beam, the Omar–Shabana beam, the 2D belt element, and planar belt drives built from them.
