#include "io/background_writer.hpp"

#include <stdexcept>

namespace gs {

BackgroundWriter::~BackgroundWriter() { wait(); }

void BackgroundWriter::run(const std::function<void()>& job) {
  std::string error;
  try {
    job();
  } catch (const std::exception& e) {
    error = e.what();
  } catch (...) {
    error = "unknown error while writing output";
  }
  if (!error.empty()) error_ += (error_.empty() ? "" : "; ") + error;
}

void BackgroundWriter::start(std::function<void()> job) {
  if (thread_.joinable()) throw std::logic_error("BackgroundWriter::start: the previous job is still in hand");
  thread_ = std::thread([this, job = std::move(job)] { run(job); });
}

void BackgroundWriter::then(std::function<void()> job) {
  if (!thread_.joinable()) return start(std::move(job));
  // The new thread joins the one in hand first: the jobs stay in order, and
  // the join orders the first job's error_ before the second's.
  thread_ = std::thread([this, before = std::move(thread_), job = std::move(job)]() mutable {
    before.join();
    run(job);
  });
}

std::string BackgroundWriter::wait() {
  if (thread_.joinable()) thread_.join();  // the join orders error_'s write before this read
  std::string error;
  error.swap(error_);
  return error;
}

}  // namespace gs
