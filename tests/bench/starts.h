// SPDX-License-Identifier: GPL-3.0-or-later
// The bench's starts mode: the non-convex sample pair's solve from B's start at 40 places, at the
// studio's preview and strip resolutions.
#pragma once

/// Solves each start `repeats` times in this process (as the studio's server does), prints the
/// Markdown table of the median over starts and the slowest start (each start's time the median
/// of its repeats) and returns the process exit code.
int runStarts(int repeats);
