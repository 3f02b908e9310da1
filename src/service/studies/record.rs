//! A study as the API shows it: the stored study with each member's status read from its
//! job, the counts, and the study's status derived from them.

use serde::{Serialize, Serializer};
use serde_json::{Map, Value};
use time::OffsetDateTime;
use uuid::Uuid;

use super::store::{AxisRecord, StoredStudy};
use crate::service::jobs::{JobStatus, Jobs};

/// Where a member is: its job's status, or `deleted` once its job has been removed on its
/// own (DELETE on the job); `None` is that deleted job.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemberStatus(pub Option<JobStatus>);

impl Serialize for MemberStatus {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.0.map_or("deleted", JobStatus::name))
    }
}

/// A study's status, derived from its members'.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StudyStatus {
    /// Every member waits for a worker.
    Queued,
    /// Some member is queued or running, and not all are queued.
    Running,
    /// Every member succeeded.
    Succeeded,
    /// Every member ended, some succeeded and some did not (failed, damaged, deleted).
    Partial,
    /// Every member ended and none succeeded or was cancelled.
    Failed,
    /// Every member ended and some were cancelled.
    Cancelled,
}

/// How many members are in each state.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Waiting.
    pub queued: usize,
    /// Running.
    pub running: usize,
    /// Succeeded.
    pub succeeded: usize,
    /// Failed.
    pub failed: usize,
    /// Cancelled.
    pub cancelled: usize,
    /// Damaged.
    pub damaged: usize,
    /// Deleted on their own.
    pub deleted: usize,
}

impl Counts {
    fn add(&mut self, status: MemberStatus) {
        let slot = match status.0 {
            Some(JobStatus::Queued) => &mut self.queued,
            Some(JobStatus::Running) => &mut self.running,
            Some(JobStatus::Succeeded) => &mut self.succeeded,
            Some(JobStatus::Failed) => &mut self.failed,
            Some(JobStatus::Cancelled) => &mut self.cancelled,
            Some(JobStatus::Damaged) => &mut self.damaged,
            None => &mut self.deleted,
        };
        *slot += 1;
    }

    fn status(&self, members: usize) -> StudyStatus {
        if self.queued == members {
            StudyStatus::Queued
        } else if self.queued + self.running > 0 {
            StudyStatus::Running
        } else if self.cancelled > 0 {
            StudyStatus::Cancelled
        } else if self.succeeded == members {
            StudyStatus::Succeeded
        } else if self.succeeded == 0 {
            StudyStatus::Failed
        } else {
            StudyStatus::Partial
        }
    }
}

/// One member as the API shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MemberRecord {
    /// Position in the expansion order, from 0.
    pub index: usize,
    /// The member's job.
    pub job_id: Uuid,
    /// Each axis's path and the value it takes here.
    pub values: Map<String, Value>,
    /// Where the member is.
    pub status: MemberStatus,
}

/// A study as the API shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyRecord {
    /// The study's id.
    pub id: Uuid,
    /// The base scene's name.
    pub name: String,
    /// Derived from the members.
    pub status: StudyStatus,
    /// When the study was accepted.
    #[serde(with = "time::serde::rfc3339")]
    pub created_at: OffsetDateTime,
    /// The axes in the order given (the first varies slowest).
    pub axes: Vec<AxisRecord>,
    /// Every member, in the expansion order.
    pub members: Vec<MemberRecord>,
    /// Members in each state.
    pub counts: Counts,
}

/// The record of a stored study, with its members' statuses read from their jobs now.
pub(super) fn record_of(stored: &StoredStudy, jobs: &Jobs) -> StudyRecord {
    let mut counts = Counts::default();
    let members: Vec<MemberRecord> = stored
        .members
        .iter()
        .map(|member| {
            let status = MemberStatus(jobs.get(member.job_id).map(|job| job.record().status));
            counts.add(status);
            MemberRecord {
                index: member.index,
                job_id: member.job_id,
                values: member.values.clone(),
                status,
            }
        })
        .collect();
    StudyRecord {
        id: stored.id,
        name: stored.name.clone(),
        status: counts.status(members.len()),
        created_at: stored.created_at,
        axes: stored.axes.clone(),
        members,
        counts,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_member_shows_its_jobs_status_or_deleted() {
        let name = |status| serde_json::to_value(MemberStatus(status)).ok();
        assert_eq!(name(Some(JobStatus::Running)), Some(Value::from("running")));
        assert_eq!(name(Some(JobStatus::Damaged)), Some(Value::from("damaged")));
        assert_eq!(name(None), Some(Value::from("deleted")));
    }
}
