//! temp
pub mod machine;
pub mod mesh_seed_refiner;
pub mod plot;
pub mod timing;
pub mod stage_times;
pub mod paper_tables;
pub mod stage_growth;
