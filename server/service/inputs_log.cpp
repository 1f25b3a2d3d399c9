#include "server/service/inputs_log.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

namespace flagsim {

InputsLog::InputsLog(Publisher& bus, const std::string& path, int64_t start_utime)
    : bus_(bus), path_(path), log_(std::make_unique<LogPublisher>(path, start_utime)) {}

void InputsLog::AdvanceTo(double time) {
  if (!log_) return;
  try {
    log_->AdvanceTo(time);
  } catch (const std::exception& error) {
    Fail(error.what());
  }
}

void InputsLog::Publish(const std::string& channel, const uint8_t* data, size_t size) {
  bus_.Publish(channel, data, size);
  if (!log_) return;
  try {
    log_->Publish(channel, data, size);
  } catch (const std::exception& error) {
    Fail(error.what());
  }
}

bool InputsLog::Close() {
  if (!log_) return !failed_;
  try {
    log_->Close();
    log_.reset();
  } catch (const std::exception& error) {
    Fail(error.what());
  }
  return !failed_;
}

void InputsLog::Fail(const std::string& what) {
  spdlog::error("recording inputs: {}; the server goes on, without a record", what);
  failed_ = true;
  log_.reset();
}

}  // namespace flagsim
