// SeqJournal: the last watch sequence number issued for each unfinished job, one small file per
// job (DATA/watch_seq/JOB_ID, 8 bytes), overwritten in place at every number issued.
//
// The store reserves numbers in blocks (EventHub::kSeqBlock) so that issuing one costs no SQLite
// transaction; the journal is what tells the next daemon, after a kill -9, which number of that
// block was really the last one issued: a write(2) to the file is in the kernel's page cache as
// soon as the call returns, so a killed process loses nothing (a power cut may: then the store's
// block end stands, as before). A file is removed once the store holds the exact number (the job
// finished). Each write opens, writes and closes, so ten thousand queued jobs hold no descriptor.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace dlmfd::server {

class SeqJournal {
 public:
  // dir is created when missing; throws std::filesystem::filesystem_error when it cannot be.
  explicit SeqJournal(std::string dir);

  // Records `seq` as the last number issued for the job; false (and the job's file removed, so
  // that no stale number remains) when it cannot be written.
  bool Record(const std::string& job_id, int64_t seq);
  // Forgets the job (its number is exact in the store now).
  void Remove(const std::string& job_id);
  // Every job's recorded number, as a daemon left them; unreadable files are skipped.
  std::map<std::string, int64_t> ReadAll() const;

 private:
  std::string Path(const std::string& job_id) const;
  std::string dir_;
};

}  // namespace dlmfd::server
