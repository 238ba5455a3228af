#include "event_hub.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <deque>
#include <optional>
#include <vector>

#include "job_proto.h"

namespace dlmfd::server {

struct EventHub::Channel {
  std::mutex mutex;
  std::string job_id;
  v1::Job job;
  std::deque<v1::WatchEvent> ring;
  std::optional<v1::WatchEvent> snapshot;
  int64_t last_seq = 0;  // last issued
  int64_t reserved = 0;  // issued numbers never exceed this (persisted)
  std::vector<std::shared_ptr<WatcherQueue>> watchers;
  std::atomic<bool> finished{false};  // read under mutex_ alone by PublishState, FindOrCreate
};

std::shared_ptr<EventHub::Channel> EventHub::Find(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  auto it = channels_.find(job_id);
  return it == channels_.end() ? nullptr : it->second;
}

std::shared_ptr<EventHub::Channel> EventHub::FindOrCreate(const JobRecord& job) {
  auto& slot = channels_[job.id];
  if (!slot || slot->finished) {
    // A channel whose final state was just delivered (not yet dropped) hands on its last number:
    // the record passed here may predate the store's copy of it.
    int64_t last = job.last_seq;
    if (slot) {
      std::lock_guard lock(slot->mutex);
      last = slot->last_seq;
    }
    slot = std::make_shared<Channel>();
    slot->job_id = job.id;
    slot->job = ToProto(job);
    slot->last_seq = last;
    slot->reserved = last;
  }
  return slot;
}

// Assigns the sequence number, keeps the event, pushes it to the watchers; those whose send token
// was taken are added to `wake`, to be woken after the channel lock is released. Channel locked by
// caller.
void EventHub::Deliver(Channel& channel, v1::WatchEvent event, WakeList& wake) {
  if (channel.last_seq >= channel.reserved) {
    channel.reserved = channel.last_seq + kSeqBlock;
    store_.SetLastSeq(channel.job_id, channel.reserved);
  }
  event.set_seq(++channel.last_seq);
  if (!journal_.Record(channel.job_id, channel.last_seq)) {
    spdlog::warn(
        "job {}: watch number {} not journaled; after a kill -9 a reconnecting watcher "
        "may be told of a Gap over numbers never issued",
        channel.job_id, channel.last_seq);
  }
  if (event.wall_time() == 0) event.set_wall_time(NowSeconds());
  if (event.has_snapshot()) {
    channel.snapshot = event;
  } else {
    channel.ring.push_back(event);
    while (channel.ring.size() > ring_size_) channel.ring.pop_front();
  }
  for (const auto& watcher : channel.watchers) {
    if (watcher->Push(event)) wake.push_back(watcher);
  }
}

namespace {
void WakeAll(const std::vector<std::shared_ptr<WatcherQueue>>& wake) {
  for (const auto& watcher : wake) watcher->Wake();
}
}  // namespace

void EventHub::PublishState(const JobRecord& job) {
  const bool final_state = IsFinished(job.state);
  std::shared_ptr<Channel> channel;
  {
    std::lock_guard lock(mutex_);
    if (final_state) {
      auto it = channels_.find(job.id);
      if (it == channels_.end() || it->second->finished) return;
      channel = it->second;
    } else {
      channel = FindOrCreate(job);
    }
  }
  WakeList wake;
  {
    std::lock_guard lock(channel->mutex);
    channel->job = ToProto(job);
    // The state event's own number: last_seq reports what was issued, never the reserved block.
    channel->job.set_last_seq(channel->last_seq + 1);
    v1::WatchEvent event;
    auto* state = event.mutable_state();
    state->set_state(channel->job.state());
    state->set_reason(channel->job.reason());  // Slurm's reason of a job that waits there
    *state->mutable_job() = channel->job;
    Deliver(*channel, std::move(event), wake);
    if (IsFinished(job.state)) {
      // No number of this channel follows: the store keeps the last one issued, and a later run
      // of the job (a retry) continues after it.
      store_.SetLastSeq(channel->job_id, channel->last_seq);
      journal_.Remove(channel->job_id);
      channel->finished = true;
      for (const auto& watcher : channel->watchers) {
        if (watcher->PushEnd()) wake.push_back(watcher);
      }
      channel->watchers.clear();
    }
  }
  if (final_state) {
    // Dropped only now, after the store holds the last number: a job read as finished and found
    // without a channel (ReportedLastSeq) finds that number in the store.
    std::lock_guard lock(mutex_);
    auto it = channels_.find(job.id);
    if (it != channels_.end() && it->second == channel) channels_.erase(it);
  }
  WakeAll(wake);
}

void EventHub::Publish(const std::string& job_id, v1::WatchEvent event) {
  auto channel = Find(job_id);
  if (!channel) return;
  WakeList wake;
  {
    std::lock_guard lock(channel->mutex);
    if (channel->finished) return;
    Deliver(*channel, std::move(event), wake);
  }
  WakeAll(wake);
}

bool EventHub::Attach(const JobRecord& job, int64_t from_seq,
                      const std::shared_ptr<WatcherQueue>& watcher) {
  std::shared_ptr<Channel> channel;
  {
    std::lock_guard lock(mutex_);
    auto it = channels_.find(job.id);
    if (it != channels_.end()) {
      channel = it->second;
    } else if (!IsFinished(job.state)) {
      // The record was read before this lock; re-read so a final state committed since is seen.
      auto fresh = store_.Get(job.id);
      if (fresh && !IsFinished(fresh->state)) channel = FindOrCreate(*fresh);
    }
  }
  bool token = false;
  auto push = [&](const v1::WatchEvent& event) { token = watcher->Push(event) || token; };
  if (!channel) {
    auto final_job = store_.Get(job.id);
    v1::WatchEvent event;
    event.set_seq(final_job->last_seq);
    event.set_wall_time(final_job->finished_time);
    auto* state = event.mutable_state();
    state->set_state(static_cast<v1::JobState>(final_job->state));
    state->set_reason(final_job->reason);
    *state->mutable_job() = ToProto(*final_job);
    push(event);
    token = watcher->PushEnd() || token;
    return token;
  }
  std::lock_guard lock(channel->mutex);
  // The current state is a summary, not a new event: it carries the watcher's own position so that
  // the sequence numbers a watcher sees never decrease.
  v1::WatchEvent current;
  current.set_seq(std::min(from_seq, channel->last_seq));
  current.set_wall_time(NowSeconds());
  auto* state = current.mutable_state();
  state->set_state(channel->job.state());
  state->set_reason(channel->job.reason());
  *state->mutable_job() = channel->job;
  state->mutable_job()->set_last_seq(channel->last_seq);
  push(current);
  const int64_t first_held =
      channel->ring.empty() ? channel->last_seq + 1 : channel->ring.front().seq();
  if (from_seq + 1 < first_held && from_seq < channel->last_seq && from_seq > 0) {
    v1::WatchEvent gap;
    gap.set_wall_time(NowSeconds());
    gap.mutable_gap()->set_from_seq(from_seq + 1);
    gap.mutable_gap()->set_to_seq(first_held - 1);
    gap.mutable_gap()->set_reason("older than the event buffer");
    push(gap);
  }
  for (const auto& event : channel->ring) {
    if (event.seq() > from_seq) push(event);
  }
  if (channel->snapshot && channel->snapshot->seq() > from_seq) push(*channel->snapshot);
  if (channel->finished) {
    token = watcher->PushEnd() || token;
  } else {
    channel->watchers.push_back(watcher);
  }
  return token;
}

void EventHub::Detach(const std::string& job_id, const WatcherQueue* watcher) {
  auto channel = Find(job_id);
  if (!channel) return;
  std::lock_guard lock(channel->mutex);
  auto& list = channel->watchers;
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (it->get() == watcher) {
      list.erase(it);
      break;
    }
  }
}

void EventHub::Recover() {
  for (const auto& [id, seq] : journal_.ReadAll()) {
    // The file outlives the store's exact number only when the daemon died in between; a job
    // deleted since has neither.
    if (auto job = store_.Get(id); job && job->last_seq != seq) {
      spdlog::info("job {}: last watch number issued {} (the store held {})", id, seq,
                   job->last_seq);
      store_.SetLastSeq(id, seq);
    }
    journal_.Remove(id);
  }
}

void EventHub::RecordIssued() {
  std::lock_guard lock(mutex_);
  for (auto& [id, channel] : channels_) {
    std::lock_guard channel_lock(channel->mutex);
    if (channel->reserved == channel->last_seq) continue;
    store_.SetLastSeq(id, channel->last_seq);
    // An event after this reserves a block again.
    channel->reserved = channel->last_seq;
  }
}

int64_t EventHub::ReportedLastSeq(const JobRecord& job) {
  if (auto channel = Find(job.id)) {
    std::lock_guard lock(channel->mutex);
    // Read as finished before its final state event was numbered: that event's number, so that a
    // finished job's last_seq always counts its final state.
    if (IsFinished(job.state) && !channel->finished) return channel->last_seq + 1;
    return channel->last_seq;
  }
  // No channel: the record may have been read while one was open (its last_seq then the end of a
  // reserved block); the store holds the last number issued once the channel is dropped.
  if (auto issued = store_.LastSeq(job.id)) return *issued;
  return job.last_seq;
}

std::optional<int64_t> EventHub::LastIssued(const std::string& job_id) {
  auto channel = Find(job_id);
  if (!channel) return std::nullopt;
  std::lock_guard lock(channel->mutex);
  return channel->last_seq;
}

size_t EventHub::ChannelCount() {
  std::lock_guard lock(mutex_);
  return channels_.size();
}

size_t EventHub::WatcherCount(const std::string& job_id) {
  auto channel = Find(job_id);
  if (!channel) return 0;
  std::lock_guard lock(channel->mutex);
  return channel->watchers.size();
}

}  // namespace dlmfd::server
