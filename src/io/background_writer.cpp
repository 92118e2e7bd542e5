#include "io/background_writer.hpp"

#include <stdexcept>

namespace gs {

BackgroundWriter::~BackgroundWriter() { wait(); }

void BackgroundWriter::start(std::function<void()> job) {
  if (thread_.joinable()) throw std::logic_error("BackgroundWriter::start: the previous job is still in hand");
  thread_ = std::thread([this, job = std::move(job)] {
    try {
      job();
    } catch (const std::exception& e) {
      error_ = e.what();
    } catch (...) {
      error_ = "unknown error while writing output";
    }
  });
}

std::string BackgroundWriter::wait() {
  if (thread_.joinable()) thread_.join();  // the join orders error_'s write before this read
  std::string error;
  error.swap(error_);
  return error;
}

}  // namespace gs
