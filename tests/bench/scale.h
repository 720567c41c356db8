// SPDX-License-Identifier: GPL-3.0-or-later
// The bench's scaling mode: forward and inverse runs at about 1k, 10k, 50k and 100k vertices.
#pragma once

#include <string>

/// Runs each case `repeats` times, each in a child process, prints the Markdown table of medians
/// (and the largest peak memory) and, when plotPath is not empty, writes the SVG plot there.
/// Returns the process exit code.
int runScale(int repeats, const std::string& plotPath);
