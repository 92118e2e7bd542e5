#pragma once
// Output files written on a thread of their own while the run steps on. One
// job at a time, in the order given: the next job starts only once the
// previous one is done. A job reads host arrays its owner keeps and reuses
// (run/run_output.hpp): the owner refills them only after wait().
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
  // Waits for the job in hand; returns its error message, once ("" when
  // it succeeded or there was none).
  std::string wait();

 private:
  std::thread thread_;
  std::string error_;  // the job's error; read after joining the thread
};

}  // namespace gs
