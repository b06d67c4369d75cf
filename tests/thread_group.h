#pragma once
// The ranks of a RenderGroup (integrators/render_group.h) as threads of one process: the render
// loop's dealing of passes and its collective decisions, tested without MPI (and under the
// sanitizers). Records travel through per-sender mailboxes; maxOverRanks is a barrier; gatherToRoot
// leaves each rank's bytes in its slot for rank 0.
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <vector>

#include "integrators/render_group.h"

namespace kasha::test {

class ThreadGroup {
 public:
  explicit ThreadGroup(int size) : size_(size), mail_(size_t(size)), gathered_(size_t(size)) {}

  class Rank final : public RenderGroup {
   public:
    Rank(ThreadGroup& g, int rank) : g_(g), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return g_.size_; }
    void send(const PassRecord& record) override {
      std::lock_guard<std::mutex> lock(g_.m_);
      g_.mail_[size_t(rank_)].push_back(record);
      g_.cv_.notify_all();
    }
    PassRecord receive(int from, int, int) override {
      std::unique_lock<std::mutex> lock(g_.m_);
      g_.cv_.wait(lock, [&] { return !g_.mail_[size_t(from)].empty(); });
      PassRecord r = std::move(g_.mail_[size_t(from)].front());
      g_.mail_[size_t(from)].pop_front();
      return r;
    }
    void maxOverRanks(std::span<int> values) override {
      std::unique_lock<std::mutex> lock(g_.m_);
      if (g_.arrived_ == 0) g_.acc_.assign(values.begin(), values.end());
      for (size_t i = 0; i < values.size(); ++i) g_.acc_[i] = std::max(g_.acc_[i], values[i]);
      const uint64_t generation = g_.generation_;
      if (++g_.arrived_ == g_.size_) {
        g_.result_ = g_.acc_;
        g_.arrived_ = 0;
        ++g_.generation_;
        g_.cv_.notify_all();
      } else {
        g_.cv_.wait(lock, [&] { return g_.generation_ != generation; });
      }
      std::copy(g_.result_.begin(), g_.result_.end(), values.begin());
    }

    void gatherToRoot(std::span<const std::byte> mine, std::span<std::byte> all) override {
      std::unique_lock<std::mutex> lock(g_.m_);
      g_.gathered_[size_t(rank_)].assign(mine.begin(), mine.end());
      g_.cv_.notify_all();
      if (rank_ != 0) return;
      g_.cv_.wait(lock, [&] {
        return std::all_of(g_.gathered_.begin(), g_.gathered_.end(), [](const auto& b) { return !b.empty(); });
      });
      for (size_t r = 0; r < g_.gathered_.size(); ++r) {
        std::copy(g_.gathered_[r].begin(), g_.gathered_[r].end(), all.begin() + std::ptrdiff_t(r * mine.size()));
        g_.gathered_[r].clear();
      }
    }

   private:
    ThreadGroup& g_;
    int rank_;
  };

 private:
  int size_;
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<std::deque<PassRecord>> mail_;  // records sent by each rank, oldest first
  int arrived_ = 0;
  uint64_t generation_ = 0;
  std::vector<int> acc_, result_;
  std::vector<std::vector<std::byte>> gathered_;  // gatherToRoot: each rank's bytes until rank 0 takes them
};

}  // namespace kasha::test
