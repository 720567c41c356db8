// SPDX-License-Identifier: GPL-3.0-or-later
// --json: the one JSON object a command prints on stdout, whatever happens (docs/cli.md,
// "Machine-readable output"; docs/cli-output.schema.json). The command's outcome fields and the
// first error it reports are gathered while it runs; finish() prints them with the exit code, so
// that success, a usage error, a bad input and a failed gate all give exactly one object.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "dform/core/status.h"

namespace dform::cli::json_summary {

/// Turns --json on for this process, for `command` (null: no command was recognised).
void enable(const std::optional<std::string>& command);
bool enabled();

/// Adds the command's outcome fields (e.g. "figures", "gate", "output") to the object.
void add(const nlohmann::json& fields);

/// Records an error as the terminal shows it: the first one is the object's "error" (its code
/// from `code`, else from the exit code; its setting, by job-file key, from `status`).
void error(const std::string& shownMessage, const Status* status = nullptr);

/// Prints the object now (a command that keeps running, the studio, prints it when it is up);
/// finish() then prints nothing more.
void printNow(int exitCode);

/// No object for this process: --help and --version print the text asked for.
void cancel();

/// Prints the object with `exitCode` unless it was printed already; returns `exitCode`.
int finish(int exitCode);

}  // namespace dform::cli::json_summary
