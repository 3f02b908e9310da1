//! The server-sent event stream of one job: `event: cycle` per solved cycle (`id:` the cycle
//! number, data the cycle record), then one `event: status` with the final job record, then
//! the end of the stream.
//!
//! A client that connects late first gets every cycle it missed: all of them, or those after
//! its `Last-Event-ID`. Each client follows the job on its own cursor and is woken by the
//! job's change signal, so any number of clients can follow one job and none misses a cycle
//! (the cycles are kept, not broadcast and dropped).

use std::collections::VecDeque;
use std::convert::Infallible;
use std::sync::Arc;
use std::time::Duration;

use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use futures_util::Stream;
use serde::Deserialize;
use tokio::sync::watch;

use super::job::{Cycle, Job, JobRecord, JobStatus};
use super::registry::Jobs;
use crate::service::blocking::blocking;

/// What every event stream is served with.
#[derive(Clone)]
pub(crate) struct Streams {
    /// Time between keep-alive comments, under the idle timeout.
    pub(crate) keep_alive: Duration,
    /// Turns true when the server shuts down, ending every stream.
    pub(crate) shutdown: watch::Receiver<bool>,
}

/// Where one client is in one job's stream.
struct Cursor {
    job: Arc<Job>,
    jobs: Arc<Jobs>,
    /// The last cycle sent (0 before the first).
    after: u64,
    changed: watch::Receiver<()>,
    shutdown: watch::Receiver<bool>,
    pending: VecDeque<Event>,
    done: bool,
}

/// The event stream of `job` for a client that has seen the cycles up to `after`, with
/// keep-alive comments. It ends after the final status, or when the server shuts down.
pub(super) fn response(jobs: Arc<Jobs>, job: Arc<Job>, after: u64, streams: &Streams) -> Response {
    Sse::new(follow(jobs, job, after, streams.shutdown.clone()))
        .keep_alive(KeepAlive::default().interval(streams.keep_alive))
        .into_response()
}

fn follow(
    jobs: Arc<Jobs>,
    job: Arc<Job>,
    after: u64,
    shutdown: watch::Receiver<bool>,
) -> impl Stream<Item = Result<Event, Infallible>> {
    let cursor = Cursor {
        changed: job.subscribe(),
        job,
        jobs,
        after,
        shutdown,
        pending: VecDeque::new(),
        done: false,
    };
    futures_util::stream::unfold(cursor, |mut cursor| async move {
        let event = cursor.next().await?;
        Some((Ok(event), cursor))
    })
}

impl Cursor {
    async fn next(&mut self) -> Option<Event> {
        loop {
            if let Some(event) = self.pending.pop_front() {
                return Some(event);
            }
            if self.done || *self.shutdown.borrow() {
                return None;
            }
            // Marked seen before reading, so a change made after the read wakes us below.
            self.changed.borrow_and_update();
            let progress = self.job.progress_after(self.after);
            let cycles = match progress.cycles {
                Some(cycles) => cycles,
                None => match self.cycles_on_disk(progress.record.status).await {
                    Some(cycles) => cycles,
                    // The stored log was damaged and the job sent back to the queue: follow
                    // its new run, unless it was deleted meanwhile.
                    None if self.jobs.get(self.job.id).is_some() => continue,
                    None => return None,
                },
            };
            for cycle in cycles {
                self.after = cycle.number;
                self.pending.push_back(cycle_event(&cycle));
            }
            if progress.record.status.is_final() {
                self.pending.push_back(status_event(&progress.record));
                self.done = true;
            }
            if self.pending.is_empty() {
                tokio::select! {
                    changed = self.changed.changed() => if changed.is_err() { return None },
                    _ = self.shutdown.changed() => return None,
                }
            }
        }
    }

    /// The cycles after `self.after` of a finished job, from its durable log. A succeeded
    /// job's log is checked against its manifest first: if it is damaged, the job is sent
    /// back to the queue and `None` returned. The log of a job that stopped early holds what
    /// was written before it stopped; an unreadable one ends the cycles there (the status
    /// event still follows).
    async fn cycles_on_disk(&self, status: JobStatus) -> Option<Vec<Cycle>> {
        let (jobs, job) = (Arc::clone(&self.jobs), Arc::clone(&self.job));
        let read = blocking(move || {
            Ok::<_, Infallible>(match status {
                JobStatus::Succeeded => match jobs.store().read_cycles(job.id) {
                    Ok(bytes) => Some(bytes),
                    Err(damage) if damage.is_read_failure() => {
                        tracing::error!(id = %job.id, "{damage}");
                        Some(Vec::new())
                    }
                    Err(damage) => {
                        jobs.rerun(&job, &damage);
                        None
                    }
                },
                JobStatus::Damaged => Some(Vec::new()),
                _ => match jobs.store().read_partial_cycles(job.id) {
                    Ok(bytes) => Some(bytes),
                    Err(e) => {
                        if e.kind() != std::io::ErrorKind::NotFound {
                            tracing::error!(id = %job.id, "cannot read the cycle log: {e}");
                        }
                        Some(Vec::new())
                    }
                },
            })
        })
        .await;
        // A read that panicked was logged as its error was made; the status event follows.
        let bytes = read.unwrap_or(Some(Vec::new()))?;
        #[derive(Deserialize)]
        struct Number {
            cycle: u64,
        }
        let text = String::from_utf8_lossy(&bytes);
        Some(
            text.lines()
                .map_while(|line| {
                    let number = serde_json::from_str::<Number>(line).ok()?.cycle;
                    Some(Cycle {
                        number,
                        json: line.into(),
                    })
                })
                .filter(|cycle| cycle.number > self.after)
                .collect(),
        )
    }
}

fn cycle_event(cycle: &Cycle) -> Event {
    Event::default()
        .event("cycle")
        .id(cycle.number.to_string())
        .data(&*cycle.json)
}

fn status_event(record: &JobRecord) -> Event {
    // A job record always serialises; the fallback keeps the stream well-formed regardless.
    let data = serde_json::to_string(record).unwrap_or_else(|_| "{}".to_owned());
    Event::default().event("status").data(data)
}
