//! The bounded queue of jobs waiting for a worker. Places are reserved before a submission
//! writes its files, so the bound holds while those writes are under way. A worker takes
//! the first job only when its estimated peak memory fits beside the running jobs' within
//! the budget, so the workers never run more than the budget holds; a job alone always
//! runs (one over the budget is refused at submit, and only a budget lowered since it was
//! accepted leaves one queued over it).

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};

use uuid::Uuid;

use super::job::Job;

/// A waiting job and its estimated peak memory, bytes.
struct Waiting {
    job: Arc<Job>,
    memory_bytes: u64,
}

struct Pending {
    jobs: VecDeque<Waiting>,
    /// Places promised to submissions still writing their files.
    reserved: usize,
    /// The estimated peak memory of the running jobs together, bytes.
    running_bytes: u64,
    stopping: bool,
}

/// Jobs in the order they were accepted; workers wait on it.
pub(super) struct Queue {
    pending: Mutex<Pending>,
    ready: Condvar,
    capacity: usize,
    memory_budget_bytes: u64,
}

/// The memory a running job holds in the budget, given back when it is dropped (the job
/// ended, or its worker panicked).
pub(super) struct Lease<'a> {
    queue: &'a Queue,
    memory_bytes: u64,
}

impl Drop for Lease<'_> {
    fn drop(&mut self) {
        let mut pending = self.queue.lock();
        pending.running_bytes = pending.running_bytes.saturating_sub(self.memory_bytes);
        drop(pending);
        // Every worker: the head may fit now, and any one of them may take it.
        self.queue.ready.notify_all();
    }
}

impl Queue {
    /// An empty queue that accepts up to `capacity` submissions and runs jobs within
    /// `memory_budget_bytes` together.
    pub(super) fn new(capacity: usize, memory_budget_bytes: u64) -> Self {
        Self {
            pending: Mutex::new(Pending {
                jobs: VecDeque::new(),
                reserved: 0,
                running_bytes: 0,
                stopping: false,
            }),
            ready: Condvar::new(),
            capacity,
            memory_budget_bytes,
        }
    }

    /// The memory the running jobs may take together, bytes.
    pub(super) fn memory_budget_bytes(&self) -> u64 {
        self.memory_budget_bytes
    }

    fn lock(&self) -> MutexGuard<'_, Pending> {
        self.pending.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// How many jobs may wait at once.
    pub(super) fn capacity(&self) -> usize {
        self.capacity
    }

    /// Promises a place to a submission; `false` when the queue is full.
    pub(super) fn reserve(&self) -> bool {
        self.reserve_many(1).is_ok()
    }

    /// Promises `count` places at once (a study's members), all or none; the places free
    /// when there are fewer.
    pub(super) fn reserve_many(&self, count: usize) -> Result<(), usize> {
        let mut pending = self.lock();
        let free = self
            .capacity
            .saturating_sub(pending.jobs.len() + pending.reserved);
        if count > free {
            return Err(free);
        }
        pending.reserved += count;
        Ok(())
    }

    /// Gives back a place whose submission failed.
    pub(super) fn release(&self) {
        self.release_many(1);
    }

    /// Gives back `count` places whose submissions failed.
    pub(super) fn release_many(&self, count: usize) {
        let mut pending = self.lock();
        pending.reserved = pending.reserved.saturating_sub(count);
    }

    /// Queues a job, of `memory_bytes` estimated peak, in the place reserved for it.
    pub(super) fn admit(&self, job: Arc<Job>, memory_bytes: u64) {
        let mut pending = self.lock();
        pending.reserved = pending.reserved.saturating_sub(1);
        pending.jobs.push_back(Waiting { job, memory_bytes });
        drop(pending);
        self.ready.notify_one();
    }

    /// Queues an accepted job without a reservation: accepted jobs are never dropped, so a
    /// queue restored at startup may exceed its capacity.
    pub(super) fn push(&self, job: Arc<Job>, memory_bytes: u64) {
        self.lock().jobs.push_back(Waiting { job, memory_bytes });
        self.ready.notify_one();
    }

    /// Takes a job out of the queue (it was cancelled). The head may have changed, so the
    /// workers look again.
    pub(super) fn remove(&self, id: Uuid) {
        self.lock().jobs.retain(|waiting| waiting.job.id != id);
        self.ready.notify_all();
    }

    /// The place of a waiting job, from 1 (the next to run); `None` when it does not wait.
    pub(super) fn position(&self, id: Uuid) -> Option<usize> {
        let pending = self.lock();
        pending
            .jobs
            .iter()
            .position(|waiting| waiting.job.id == id)
            .map(|i| i + 1)
    }

    /// The place of every waiting job, from 1.
    pub(super) fn positions(&self) -> HashMap<Uuid, usize> {
        let pending = self.lock();
        pending
            .jobs
            .iter()
            .enumerate()
            .map(|(i, waiting)| (waiting.job.id, i + 1))
            .collect()
    }

    /// The next job and its lease on the memory budget, waiting until there is one that
    /// fits beside the running jobs (first come, first served: a large job at the head is
    /// not overtaken, so it cannot starve); `None` once stopping.
    pub(super) fn next(&self) -> Option<(Arc<Job>, Lease<'_>)> {
        let mut pending = self.lock();
        loop {
            if pending.stopping {
                return None;
            }
            let fits = pending.jobs.front().is_some_and(|head| {
                pending.running_bytes == 0
                    || pending.running_bytes.saturating_add(head.memory_bytes)
                        <= self.memory_budget_bytes
            });
            if let Some(Waiting { job, memory_bytes }) =
                fits.then(|| pending.jobs.pop_front()).flatten()
            {
                pending.running_bytes = pending.running_bytes.saturating_add(memory_bytes);
                let lease = Lease {
                    queue: self,
                    memory_bytes,
                };
                return Some((job, lease));
            }
            pending = self
                .ready
                .wait(pending)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    /// Wakes every waiting worker with `None`, now and from now on.
    pub(super) fn stop(&self) {
        self.lock().stopping = true;
        self.ready.notify_all();
    }
}
