//! The bounded queue of jobs waiting for a worker. Places are reserved before a submission
//! writes its files, so the bound holds while those writes are under way.

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};

use uuid::Uuid;

use super::job::Job;

struct Pending {
    jobs: VecDeque<Arc<Job>>,
    /// Places promised to submissions still writing their files.
    reserved: usize,
    stopping: bool,
}

/// Jobs in the order they were accepted; workers wait on it.
pub(super) struct Queue {
    pending: Mutex<Pending>,
    ready: Condvar,
    capacity: usize,
}

impl Queue {
    /// An empty queue that accepts up to `capacity` submissions.
    pub(super) fn new(capacity: usize) -> Self {
        Self {
            pending: Mutex::new(Pending {
                jobs: VecDeque::new(),
                reserved: 0,
                stopping: false,
            }),
            ready: Condvar::new(),
            capacity,
        }
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

    /// Queues a job in the place reserved for it.
    pub(super) fn admit(&self, job: Arc<Job>) {
        let mut pending = self.lock();
        pending.reserved = pending.reserved.saturating_sub(1);
        pending.jobs.push_back(job);
        drop(pending);
        self.ready.notify_one();
    }

    /// Queues an accepted job without a reservation: accepted jobs are never dropped, so a
    /// queue restored at startup may exceed its capacity.
    pub(super) fn push(&self, job: Arc<Job>) {
        self.lock().jobs.push_back(job);
        self.ready.notify_one();
    }

    /// Takes a job out of the queue (it was cancelled).
    pub(super) fn remove(&self, id: Uuid) {
        self.lock().jobs.retain(|queued| queued.id != id);
    }

    /// The place of a waiting job, from 1 (the next to run); `None` when it does not wait.
    pub(super) fn position(&self, id: Uuid) -> Option<usize> {
        let pending = self.lock();
        pending
            .jobs
            .iter()
            .position(|job| job.id == id)
            .map(|i| i + 1)
    }

    /// The place of every waiting job, from 1.
    pub(super) fn positions(&self) -> HashMap<Uuid, usize> {
        let pending = self.lock();
        pending
            .jobs
            .iter()
            .enumerate()
            .map(|(i, job)| (job.id, i + 1))
            .collect()
    }

    /// The next job, waiting for one; `None` once stopping.
    pub(super) fn next(&self) -> Option<Arc<Job>> {
        let mut pending = self.lock();
        loop {
            if pending.stopping {
                return None;
            }
            if let Some(job) = pending.jobs.pop_front() {
                return Some(job);
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
