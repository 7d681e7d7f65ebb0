//! Light selection (`warpcore::lights`): one test target, one module per table.

mod alias;
mod tree;
