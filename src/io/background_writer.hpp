#pragma once
// Output files written on a thread of their own while the run steps on. One
// job at a time, in the order given: the next job starts only once the
// previous one is done (start() after wait(), or then()). A job reads host
// arrays its owner keeps and reuses (run/run_output.hpp): the owner refills
// them only after wait().
#include <functional>
#include <string>
#include <thread>

namespace gs {

class BackgroundWriter {
 public:
  BackgroundWriter() = default;
  // Waits for the job in hand (its files are complete, or it failed).
  ~BackgroundWriter();
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;

  // Starts `job` on the writer's thread; the previous job must be done
  // (wait() first). An exception thrown by the job is kept for wait().
  void start(std::function<void()> job);
  // Starts `job` once the job in hand is done (at once when there is none),
  // without waiting for it here: for a job that reads nothing the one in
  // hand is still reading. It runs even if the one before failed.
  void then(std::function<void()> job);
  // Waits for the jobs in hand; returns their error messages, once ("" when
  // they succeeded or there was none; several joined by "; ").
  std::string wait();

 private:
  void run(const std::function<void()>& job);  // on the writer's thread: job(), its error kept
  std::thread thread_;
  std::string error_;  // the jobs' errors; read after joining the thread
};

}  // namespace gs
