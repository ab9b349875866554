#pragma once
// What `bench merge` accepts in a shard's table rows before copying them into the merged
// CSV (docs/bad-input.md, "Round 3"): rows are joined verbatim, so a newline inside a row
// would add rows, NUL or ESC would reach whoever views the file, and a text cell starting
// "=cmd|..." would run as a formula in a spreadsheet.
#include <string>

#include "foveal/core/error.hpp"

namespace foveal::bench {

/// Checks one line of a table (its header, or a row): no control character (below 0x20,
/// DEL) in any cell, and no text cell starting with =, +, - or @ (a number such as -3.5
/// or -inf is a number, not text). `where` names the shard file, table and line;
/// `columns` is the table's header (names the column), empty when checking the header.
Status check_csv_line(const std::string& line, const std::string& columns, const std::string& where);

}  // namespace foveal::bench
