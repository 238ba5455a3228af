#include "event_hub.h"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <vector>

#include "job_proto.h"

namespace dlmfd::server {
namespace fs = std::filesystem;

struct EventHub::Channel {
  explicit Channel(std::string dir)
      : log(std::move(dir)) {}
  std::mutex mutex;
  std::string job_id;
  v1::Job job;
  WatchLog log;
  int64_t last_seq = 0;                          // last issued
  std::map<std::string, int64_t> high_water;     // lane -> last step published
  std::map<std::string, int64_t> source_offset;  // solver event file -> offset past the last read
  std::vector<std::shared_ptr<WatcherQueue>> watchers;
  bool unlogged = false;              // an event could not be logged (warned once)
  std::atomic<bool> finished{false};  // read under mutex_ alone by PublishState, FindOrCreate
};

namespace {

void WakeAll(const std::vector<std::shared_ptr<WatcherQueue>>& wake) {
  for (const auto& watcher : wake) watcher->Wake();
}

// The current state of a job as the head of a watch: a summary, numbered 0 like a Gap (it is not
// an event of the sequence: the events a watcher has seen keep their own numbers).
v1::WatchEvent Summary(const v1::Job& job, double now) {
  v1::WatchEvent summary;
  summary.set_wall_time(now);
  auto* state = summary.mutable_state();
  state->set_state(job.state());
  state->set_reason(job.reason());
  *state->mutable_job() = job;
  return summary;
}

// The numbers an older daemon journaled in DATA/watch_seq (one 8-byte file per job).
std::map<std::string, int64_t> ReadLegacyJournal(const std::string& dir) {
  std::map<std::string, int64_t> out;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const int fd = open(entry.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    unsigned char bytes[sizeof(int64_t)];
    const ssize_t got = pread(fd, bytes, sizeof(bytes), 0);
    close(fd);
    if (got != static_cast<ssize_t>(sizeof(bytes))) continue;
    int64_t seq = 0;
    std::memcpy(&seq, bytes, sizeof(seq));
    if (seq > 0) out[entry.path().filename().string()] = seq;
  }
  return out;
}

}  // namespace

std::shared_ptr<EventHub::Channel> EventHub::Find(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  auto it = channels_.find(job_id);
  return it == channels_.end() ? nullptr : it->second;
}

std::shared_ptr<EventHub::Channel> EventHub::FindOrCreate(const JobRecord& job) {
  auto& slot = channels_[job.id];
  if (slot && !slot->finished) return slot;
  auto channel = std::make_shared<Channel>(job_dir_(job.id));
  channel->job_id = job.id;
  channel->job = ToProto(job, clock_.Now());
  if (slot) {
    // A channel whose final state was just delivered (not yet dropped) hands on what it knows: its
    // last event may not be in the record passed here.
    std::lock_guard lock(slot->mutex);
    channel->last_seq = slot->last_seq;
    channel->high_water = slot->high_water;
    channel->source_offset = slot->source_offset;
  } else {
    const WatchLogState logged = channel->log.Recover();
    channel->last_seq = std::max(logged.last_seq, job.last_seq);
    channel->high_water = logged.high_water;
    channel->source_offset = logged.source_offset;
  }
  slot = channel;
  return slot;
}

// Numbers the event, logs it, pushes it to the watchers; those whose send token was taken are
// added to `wake`, to be woken after the channel lock is released. Channel locked by caller.
void EventHub::Deliver(Channel& channel, v1::WatchEvent event, const LogOrigin& origin,
                       bool new_timeline, WakeList& wake) {
  event.set_seq(++channel.last_seq);
  if (event.wall_time() == 0) event.set_wall_time(clock_.Now());
  if (new_timeline) channel.high_water.clear();
  if (!origin.lane.empty()) channel.high_water[origin.lane] = origin.step;
  if (!origin.source.empty()) channel.source_offset[origin.source] = origin.source_offset;
  if (!channel.log.Append(event, origin, new_timeline) && !channel.unlogged) {
    channel.unlogged = true;
    spdlog::warn(
        "job {}: watch event {} cannot be written to its watch log ({}); a watcher that "
        "reconnects is told of a Gap for the events not logged",
        channel.job_id, channel.last_seq, std::strerror(errno));
  }
  for (const auto& watcher : channel.watchers) {
    if (watcher->Push(event)) wake.push_back(watcher);
  }
}

void EventHub::PublishState(const JobRecord& job, bool new_timeline) {
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
    channel->job = ToProto(job, clock_.Now());
    // The state event's own number: last_seq reports what was issued.
    channel->job.set_last_seq(channel->last_seq + 1);
    v1::WatchEvent event;
    auto* state = event.mutable_state();
    state->set_state(channel->job.state());
    state->set_reason(channel->job.reason());  // Slurm's reason of a job that waits there
    *state->mutable_job() = channel->job;
    // The store learns a finished job's last number before the log holds its event: a daemon
    // killed in between reports a number whose event a watcher then gets as a Gap, never a number
    // issued twice.
    if (final_state) store_.SetLastSeq(channel->job_id, channel->last_seq + 1);
    Deliver(*channel, std::move(event), {}, new_timeline, wake);
    if (final_state) {
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

bool EventHub::Publish(const std::string& job_id, v1::WatchEvent event, const LogOrigin& origin) {
  auto channel = Find(job_id);
  if (!channel) return false;
  WakeList wake;
  {
    std::lock_guard lock(channel->mutex);
    if (channel->finished) return false;
    if (!origin.lane.empty()) {
      auto it = channel->high_water.find(origin.lane);
      if (it != channel->high_water.end() && origin.step <= it->second) {
        // Published already, from the run before a resume: read past, not sent again.
        if (!origin.source.empty()) channel->source_offset[origin.source] = origin.source_offset;
        return false;
      }
    }
    Deliver(*channel, std::move(event), origin, false, wake);
  }
  WakeAll(wake);
  return true;
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
  if (!channel) {
    // Finished: its final state, then what the log holds after from_seq (a number it lacks comes
    // as a Gap), then the end.
    const auto final_job = store_.Get(job.id);
    if (!final_job) return false;
    v1::Job shown = ToProto(*final_job, clock_.Now());
    bool token = watcher->Start(Summary(shown, clock_.Now()), from_seq, final_job->last_seq);
    token = watcher->PushEnd() || token;
    return token;
  }
  std::lock_guard lock(channel->mutex);
  v1::Job shown = channel->job;
  shown.set_last_seq(channel->last_seq);
  bool token = watcher->Start(Summary(shown, clock_.Now()), from_seq, channel->last_seq);
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

std::optional<int64_t> EventHub::SourceOffset(const JobRecord& job, const std::string& source) {
  if (auto channel = Find(job.id)) {
    std::lock_guard lock(channel->mutex);
    auto it = channel->source_offset.find(source);
    if (it == channel->source_offset.end()) return std::nullopt;
    return it->second;
  }
  const WatchLogState logged = WatchLog(job_dir_(job.id)).Recover();
  auto it = logged.source_offset.find(source);
  if (it == logged.source_offset.end()) return std::nullopt;
  return it->second;
}

void EventHub::Recover(const std::string& legacy_journal_dir) {
  for (const auto& [id, seq] : ReadLegacyJournal(legacy_journal_dir)) {
    // The store held the end of a reserved block; the journal the number really issued.
    if (auto job = store_.Get(id); job && job->last_seq != seq) store_.SetLastSeq(id, seq);
  }
  std::error_code error;
  fs::remove_all(legacy_journal_dir, error);
  for (const std::string& id : store_.UnfinishedJobIds()) {
    const int64_t logged = WatchLog(job_dir_(id)).Recover().last_seq;
    if (auto job = store_.Get(id); job && logged > job->last_seq) {
      spdlog::info("job {}: last watch number issued {} (the store held {})", id, logged,
                   job->last_seq);
      store_.SetLastSeq(id, logged);
    }
  }
}

void EventHub::RecordIssued() {
  std::lock_guard lock(mutex_);
  for (auto& [id, channel] : channels_) {
    std::lock_guard channel_lock(channel->mutex);
    store_.SetLastSeq(id, channel->last_seq);
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
