// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Common/Threads.h"

#include <condition_variable>
#include <cstdint>
#include <mutex>

#include <unistd.h>

namespace spectral
{
namespace detail
{
namespace
{
/**
 * The helper threads of ForEachRowRange, kept waiting between its calls. One caller at a time
 * uses them (the others, concurrent or nested, start threads of their own); they are started on
 * first use, as many as the largest call asked for, and joined when the program ends (not in a
 * child of fork(), which has none of them).
 */
class HelperPool
{
public:
  static HelperPool& Instance()
  {
    // Deleted at exit by the process that made it. A child of fork() leaves it alone: the
    // threads it would join, and those its condition variables count as waiting, are the
    // parent's (destroying them hung the child's exit).
    struct Owner
    {
      HelperPool* Pool = new HelperPool;
      ~Owner()
      {
        if (getpid() == this->Pool->Process)
        {
          delete this->Pool;
        }
      }
    };
    static Owner owner;
    return *owner.Pool;
  }

  HelperPool(const HelperPool&) = delete;
  HelperPool& operator=(const HelperPool&) = delete;

  ~HelperPool()
  {
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      this->Stop = true;
    }
    this->Wake.notify_all();
    for (std::thread& thread : this->Threads)
    {
      if (thread.joinable())
      {
        thread.join();
      }
    }
  }

  bool Run(int helpers, const std::function<void(int)>& run)
  {
    std::unique_lock<std::mutex> busy(this->Busy, std::try_to_lock);
    // In a child of fork() the threads of the parent do not exist.
    if (!busy.owns_lock() || getpid() != this->Process)
    {
      return false;
    }
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      try
      {
        while (static_cast<int>(this->Threads.size()) < helpers)
        {
          this->Threads.emplace_back(
            &HelperPool::Loop, this, static_cast<int>(this->Threads.size()), this->Generation);
        }
      }
      catch (const std::system_error&)
      {
        return false; // no more threads to be had; those started wait for the next call
      }
      this->Task = &run;
      this->Active = helpers;
      this->Remaining = helpers;
      ++this->Generation;
    }
    this->Wake.notify_all();
    run(0);
    std::unique_lock<std::mutex> lock(this->Lock);
    this->Done.wait(lock, [this] { return this->Remaining == 0; });
    this->Task = nullptr;
    return true;
  }

private:
  HelperPool() = default;

  /// Helper `index` runs part index + 1 of every call with more than `index` helpers, from the
  /// call after `seen`.
  void Loop(int index, std::uint64_t seen)
  {
    std::unique_lock<std::mutex> lock(this->Lock);
    for (;;)
    {
      this->Wake.wait(lock, [&] { return this->Stop || this->Generation != seen; });
      if (this->Stop)
      {
        return;
      }
      seen = this->Generation;
      if (index >= this->Active)
      {
        continue;
      }
      const std::function<void(int)>& task = *this->Task;
      lock.unlock();
      task(index + 1);
      lock.lock();
      if (--this->Remaining == 0)
      {
        this->Done.notify_one();
      }
    }
  }

  const pid_t Process = getpid();
  std::mutex Busy; ///< held by the caller whose parts the helpers run
  std::mutex Lock; ///< guards everything below
  std::condition_variable Wake;
  std::condition_variable Done;
  std::vector<std::thread> Threads;
  const std::function<void(int)>* Task = nullptr;
  int Active = 0;    ///< helpers that take part in the current call
  int Remaining = 0; ///< of those, the ones not finished
  std::uint64_t Generation = 0;
  bool Stop = false;
};
} // namespace

//------------------------------------------------------------------------------
bool RunOnHelpers(int helpers, const std::function<void(int)>& run)
{
  return HelperPool::Instance().Run(helpers, run);
}
} // namespace detail
} // namespace spectral
