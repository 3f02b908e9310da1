//! Printable reports over HTTP (`docs/report.md`): a job's, a comparison of jobs' and a
//! study's, made by [`crate::report`] from what the jobs, their measurements and the
//! studies hold. Nothing is stored: a report is made when it is asked for.

mod routes;

pub(crate) use routes::endpoints;
