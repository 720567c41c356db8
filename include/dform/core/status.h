// SPDX-License-Identifier: GPL-3.0-or-later
// Errors from bad user input. A broken invariant is a bug (assert); a solve that does not converge
// is a result with its summary; everything the user can fix is a Status naming the file and
// problem. A message about a setting names it by mention() (core/setting.h), which each shell
// words its own way.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "dform/core/setting.h"

namespace dform {

/// Error kinds. The CLI maps each to a documented exit code (see README "Exit codes").
enum class ErrorCode {
  Ok = 0,
  Usage,            ///< a bad command line or option value
  InputUnreadable,  ///< a missing or unreadable file, or one that is not of the expected format
  InputInvalid,     ///< a readable file whose content cannot be used (open, self-intersecting, ...)
  SolveFailed,      ///< the solver could not produce a usable result
  OutputFailed,     ///< an output file could not be written
  GateFailed,       ///< the result did not pass the quality gate
  Interrupted,      ///< the run was interrupted by the user
  Internal,         ///< a bug
};

/// The outcome of a step that returns no value: ok, or an ErrorCode with a message naming the file
/// or setting and the problem. [[nodiscard]]: a dropped Status is a lost error.
class [[nodiscard]] Status {
 public:
  Status() = default;
  /// An error of kind `code` (not Ok) with its message.
  Status(ErrorCode code, std::string message) : code_(code), message_(std::move(message)) {}

  /// Success: code Ok, no message.
  static Status ok() { return {}; }
  /// Whether this is success.
  bool isOk() const { return code_ == ErrorCode::Ok; }
  /// The kind of error (Ok on success), which decides the exit code.
  ErrorCode code() const { return code_; }
  /// The message, each setting it mentions named by its job-file key ("fit_perimeter").
  std::string message() const { return plainSettings(message_); }
  /// The message, each setting it mentions as a shell names it (`words`).
  std::string message(const SettingWords& words) const { return wordSettings(message_, words); }
  /// The message as written, its mentions kept: for a Status that adds to it.
  const std::string& text() const { return message_; }
  /// The first setting the message mentions (the one it is about, or the one to change).
  std::optional<Setting> setting() const { return firstMention(message_); }

 private:
  ErrorCode code_ = ErrorCode::Ok;
  std::string message_;
};

/// Thrown by Result::value() on a Result that holds an error, as std::expected throws
/// bad_expected_access: reading a value that is not there is a bug of the caller, who checks
/// isOk() first. what() names the error the Result held.
class BadResultAccess : public std::logic_error {
 public:
  /// The error `status` the Result held.
  explicit BadResultAccess(Status status)
      : std::logic_error("the value of a failed result was read: " + status.message()),
        status_(std::move(status)) {}
  /// The error the Result held.
  const Status& status() const { return status_; }

 private:
  Status status_;
};

/// A value or the Status that explains why there is none. value() on an error throws
/// BadResultAccess, in every build. A Result made from a Status holds an error: one made from
/// Status::ok() (a bug of the caller, who has no value to give) holds an Internal error saying so,
/// never a default value that reads as a result.
template <typename T>
class [[nodiscard]] Result {
 public:
  /// A success holding `value`.
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit by design
  /// An error: `status`, or an Internal error when `status` is ok.
  Result(Status status)  // NOLINT: implicit by design
      : status_(status.isOk() ? Status(ErrorCode::Internal,
                                       "a result was made from an ok status, without a value")
                              : std::move(status)) {}

  /// Whether a value is held.
  bool isOk() const { return status_.isOk(); }
  /// Ok with a value, else the error.
  const Status& status() const { return status_; }
  /// The value; throws BadResultAccess on an error.
  const T& value() const& { return checked(), *value_; }
  /// The value; throws BadResultAccess on an error.
  T& value() & { return checked(), *value_; }
  /// The value, moved out; throws BadResultAccess on an error.
  T&& value() && { return checked(), std::move(*value_); }

 private:
  void checked() const {
    if (!isOk()) throw BadResultAccess(status_);
  }

  std::optional<T> value_;
  Status status_;
};

}  // namespace dform
