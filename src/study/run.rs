//! Running a study's members on worker threads, each member a plain
//! [`crate::simulation::run`].

use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

use crate::simulation::{Plan, RunOptions, SimulationError, SimulationResult, run_with};

use super::Member;

/// How one member ended.
#[derive(Debug)]
pub struct MemberOutcome {
    /// The member's position in the expansion order.
    pub index: usize,
    /// Its result, or why it stopped (cancelled ones included).
    pub result: Result<SimulationResult, SimulationError>,
}

/// Runs `members` on `workers` threads (at least one, at most one per member), each taking
/// the next member not yet started. A member that fails leaves the others running. Once
/// `cancel` is set, running members stop at their next cycle and the ones not started end
/// as cancelled with no cycles done. `on_done` is called on this thread as each member
/// ends, in the order they end; the outcomes come back in the members' order.
pub fn run_members(
    members: &[Member],
    workers: usize,
    cancel: &AtomicBool,
    on_done: &mut dyn FnMut(&Member, &MemberOutcome),
) -> Vec<MemberOutcome> {
    let next = AtomicUsize::new(0);
    let (sender, receiver) = mpsc::channel();
    let mut outcomes: Vec<Option<MemberOutcome>> = members.iter().map(|_| None).collect();
    let threads = workers.clamp(1, members.len().max(1));
    // Each member's solves get their share of the cores (`numerics.threads: "auto"`).
    let options = RunOptions {
        concurrent_runs: NonZeroUsize::new(threads).unwrap_or(NonZeroUsize::MIN),
        ..RunOptions::default()
    };
    let options = &options;
    std::thread::scope(|scope| {
        for _ in 0..threads {
            let sender = sender.clone();
            let next = &next;
            scope.spawn(move || {
                loop {
                    let index = next.fetch_add(1, Ordering::Relaxed);
                    let Some(member) = members.get(index) else {
                        break;
                    };
                    let result = if cancel.load(Ordering::Relaxed) {
                        Err(SimulationError::Cancelled { cycles_done: 0 })
                    } else {
                        // A member's scene is data (a Slurm file, a job's record): it is
                        // checked again where it runs.
                        Plan::new(member.scene.clone())
                            .map_err(SimulationError::from)
                            .and_then(|plan| run_with(&plan, options, &mut |_| {}, cancel))
                    };
                    // The receiver lives until every worker has ended.
                    let _ = sender.send(MemberOutcome { index, result });
                }
            });
        }
        drop(sender);
        for outcome in receiver {
            on_done(&members[outcome.index], &outcome);
            let slot = outcome.index;
            outcomes[slot] = Some(outcome);
        }
    });
    outcomes.into_iter().flatten().collect()
}
