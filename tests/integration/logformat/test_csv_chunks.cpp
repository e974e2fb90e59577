// SPDX-License-Identifier: MIT
// The CSV reader streams long logs in blocks of whole lines and parses each block in ranges on several
// threads (io/csv_table.hpp, CsvChunking). With blocks and ranges made tiny, every boundary case occurs in
// a small file: lines cut by a block end, a line longer than a block, ranges inside a block; the table must
// hold exactly the values written (known by construction, not read back from the reader), and an error
// must name the same line whatever the chunking.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"
#include "io/csv_pieces.hpp"
#include "io/csv_table.hpp"
#include "scratch_directory.hpp"

namespace {

using namespace jacobid;

std::string write(const std::string& name, const std::string& text) {
    const std::string path = (test::scratch_directory() / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Row i: t = i / 1000 (printed with 3 decimals), a = i + 0.25, b = -i / 8, all exact in binary.
std::string rows_text(std::size_t rows, bool final_newline, const std::string& line_end = "\n") {
    std::string text = "t, a ,b" + line_end;
    for (std::size_t i = 0; i < rows; ++i) {
        text += std::to_string(i / 1000) + "." + std::string(3 - std::to_string(i % 1000).size(), '0') + std::to_string(i % 1000) + "," +
                std::to_string(static_cast<double>(i) + 0.25) + ", " + std::to_string(-static_cast<double>(i) / 8.0);
        if (i + 1 < rows || final_newline) text += line_end;
    }
    return text;
}

void expect_rows(const io::CsvTable& table, std::size_t rows) {
    ASSERT_EQ(table.rows(), rows);
    ASSERT_EQ(table.header(), (std::vector<std::string>{"t", "a", "b"}));
    for (std::size_t i = 0; i < rows; ++i) {
        ASSERT_EQ(table.column("t")[i], std::stod(std::to_string(i / 1000) + "." + std::string(3 - std::to_string(i % 1000).size(), '0') +
                                                  std::to_string(i % 1000)))
            << i;
        ASSERT_EQ(table.column("a")[i], static_cast<double>(i) + 0.25) << i;
        ASSERT_EQ(table.column("b")[i], -static_cast<double>(i) / 8.0) << i;
    }
}

const io::CsvChunking kChunkings[] = {
    {},                // one block, one range (the file is small)
    {4096, 512, 4},    // many blocks, several ranges per block
    {97, 31, 3},       // blocks shorter than a line: a line spans several reads
    {1000, 1, 0},      // a range per line, one thread per core
};

TEST(CsvChunks, EveryChunkingReadsExactlyTheValuesWritten) {
    for (const bool final_newline : {true, false}) {
        for (const std::string line_end : {"\n", "\r\n"}) {
            const std::string path = write("rows.csv", rows_text(1501, final_newline, line_end));
            for (const auto& chunking : kChunkings) {
                SCOPED_TRACE(testing::Message() << "block " << chunking.block_bytes << " range " << chunking.range_bytes << " newline "
                                                << final_newline << " crlf " << (line_end.size() == 2));
                expect_rows(io::read_csv(path, chunking), 1501);
            }
            const std::string text = rows_text(1501, final_newline, line_end);
            expect_rows(io::parse_csv(text, "text", {4096, 300, 4}), 1501);
        }
    }
}

TEST(CsvChunks, AHeaderAloneAndOneTrailingEmptyLineAreFine) {
    for (const auto& chunking : kChunkings) {
        EXPECT_EQ(io::read_csv(write("header.csv", "t,a,b"), chunking).rows(), 0u);
        EXPECT_EQ(io::read_csv(write("header_nl.csv", "t,a,b\n"), chunking).rows(), 0u);
        expect_rows(io::read_csv(write("trailing.csv", rows_text(500, true) + "\n"), chunking), 500);
    }
}

// The message names the file's line, the first bad one when there are several, whatever the chunking.
TEST(CsvChunks, ErrorsNameTheSameLineWhateverTheChunking) {
    std::string text = rows_text(2000, true);
    const auto replace_line = [](std::string t, std::size_t line, const std::string& with) {
        std::size_t pos = 0;
        for (std::size_t l = 1; l < line; ++l) pos = t.find('\n', pos) + 1;
        return t.replace(pos, t.find('\n', pos) - pos, with);
    };
    struct Case {
        std::string text, expected;
    };
    const Case cases[] = {
        {replace_line(text, 1718, "1.716,abc,1"), "bad.csv:1718: column 'a': expected a number, got 'abc'"},
        {replace_line(replace_line(text, 1500, "1.498,1"), 1234, "1.232,1,2,3"), "bad.csv:1234: expected 3 columns, found 4"},
        {replace_line(text, 1999, ""), "bad.csv:1999: empty line inside the data"},
        {text + "\n\n", "bad.csv:2002: empty line inside the data"},  // the first of two empty lines at the end
        {replace_line(text, 2001, "1.999,nan,0"), "bad.csv:2001: column 'a': value 'nan' is not finite"},
    };
    for (const Case& c : cases) {
        const std::string path = write("bad.csv", c.text);
        for (const auto& chunking : kChunkings) {
            try {
                (void)io::read_csv(path, chunking);
                ADD_FAILURE() << "no error for " << c.expected << " (block " << chunking.block_bytes << ")";
            } catch (const InputError& e) {
                EXPECT_EQ(std::string(e.what()).rfind(path + c.expected.substr(7), 0), 0u)
                    << e.what() << " expected " << c.expected << " (block " << chunking.block_bytes << ")";
            }
        }
    }
}

// A column the reader is told not to keep (identify keeps the 13 of a simulated 6-axis log's 25 it reads) is
// still checked cell by cell, but holds nothing: has_column is false for it, as if the file lacked it, and
// the kept columns hold exactly the values written, whatever the chunking.
TEST(CsvChunks, ColumnsNotKeptAreCheckedButNotHeld) {
    const std::string path = write("rows.csv", rows_text(1501, true));
    const io::CsvColumnFilter keep = [](const std::string& name) { return name != "a"; };
    for (const auto& chunking : kChunkings) {
        const io::CsvTable table = io::read_csv(path, chunking, keep);
        ASSERT_EQ(table.rows(), 1501u);
        EXPECT_EQ(table.header(), (std::vector<std::string>{"t", "a", "b"}));
        EXPECT_TRUE(table.has_column("t"));
        EXPECT_FALSE(table.has_column("a"));
        EXPECT_TRUE(table.column(1).empty());
        EXPECT_THROW((void)table.column("a"), std::logic_error);
        for (std::size_t i = 0; i < 1501; ++i) ASSERT_EQ(table.column("b")[i], -static_cast<double>(i) / 8.0) << i;
    }
    // The column not kept is still read: its bad cell is the file's error, on its line.
    std::string text = rows_text(1501, true);
    const std::size_t line_start = text.find("\n1.000,") + 1;
    text.replace(line_start, text.find('\n', line_start) - line_start, "1.000,abc,1");
    const std::string bad = write("bad_unkept.csv", text);
    for (const auto& chunking : kChunkings) {
        try {
            (void)io::read_csv(bad, chunking, keep);
            ADD_FAILURE() << "no error for the bad cell of a column not kept";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), bad + ":1002: column 'a': expected a number, got 'abc'");
        }
    }
    // A header with none of the names a command reads is the file's fault (a gzip log read as one odd column
    // was "internal error ... told to keep none", exit 3): an InputError naming the header (issue 36).
    try {
        (void)io::read_csv(path, {}, [](const std::string&) { return false; });
        ADD_FAILURE() << "no error for a header without a kept column";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path + ":1: none of the header's columns (t,a,b) is one this command reads");
    }
}

// A column released after use (identify's time column) frees its values and reads as not kept; the rows are
// still counted (from the next loaded column), and the last loaded column is never released.
TEST(CsvChunks, AReleasedColumnIsNoLongerHeld) {
    io::CsvTable table = io::read_csv(write("release.csv", rows_text(301, true)));
    table.release("t");
    EXPECT_FALSE(table.has_column("t"));
    EXPECT_TRUE(table.column(0).empty());
    EXPECT_EQ(table.column(0).capacity(), 0u) << "its memory freed, not only emptied";
    EXPECT_EQ(table.rows(), 301u);
    EXPECT_EQ(table.column("b")[300], -300.0 / 8.0);
    table.release("a");
    table.release("b");  // the last one: kept
    EXPECT_TRUE(table.has_column("b"));
    EXPECT_EQ(table.rows(), 301u);
    table.release("no such column");
}

// --- Pieces (io/csv_pieces.hpp): a long log read a piece at a time ---------------------------------------

// Every piece of `path` at `piece_rows`, read with `chunking`.
std::vector<io::CsvTable> pieces_of(const std::string& path, std::size_t piece_rows, const io::CsvChunking& chunking = {}) {
    io::CsvPieceReader reader(path, chunking);
    reader.set_piece_rows(piece_rows);
    std::vector<io::CsvTable> pieces;
    for (io::CsvTable piece; reader.next(piece);) pieces.push_back(std::move(piece));
    return pieces;
}

// Row i's values (rows_text), at row r of a table, and its line number (header line 1).
void expect_row(const io::CsvTable& table, std::size_t r, std::size_t i) {
    ASSERT_EQ(table.column("a")[r], static_cast<double>(i) + 0.25) << i;
    ASSERT_EQ(table.column("b")[r], -static_cast<double>(i) / 8.0) << i;
    ASSERT_EQ(table.line_of_row(r), i + 2) << i;
}

TEST(CsvPieces, ConsecutivePiecesShareOneRowAndTogetherHoldEveryRowOnce) {
    const std::string path = write("pieces.csv", rows_text(1501, true));
    for (const auto& chunking : kChunkings) {
        SCOPED_TRACE(testing::Message() << "block " << chunking.block_bytes << " range " << chunking.range_bytes);
        const std::vector<io::CsvTable> pieces = pieces_of(path, 100, chunking);
        // 100 rows, then 99 new ones after the shared row: 1 + ceil(1401 / 99) pieces.
        ASSERT_EQ(pieces.size(), 16u);
        std::size_t next = 0;  // the row of the file the next new row must be
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const io::CsvTable& piece = pieces[k];
            ASSERT_LE(piece.rows(), 100u);
            ASSERT_EQ(piece.header(), (std::vector<std::string>{"t", "a", "b"}));
            std::size_t r = 0;
            if (k > 0) {
                expect_row(piece, 0, next - 1);  // the previous piece's last row, again
                r = 1;
            }
            for (; r < piece.rows(); ++r) expect_row(piece, r, next++);
        }
        EXPECT_EQ(next, 1501u);
    }
}

TEST(CsvPieces, AShortRestOfTheFileStaysInTheLastPiece) {
    // 1010 rows at 1000 per piece: the 10 left (1 % of a piece) are not a piece of their own.
    const std::vector<io::CsvTable> pieces = pieces_of(write("rest.csv", rows_text(1010, false)), 1000, {4096, 512, 2});
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_EQ(pieces[0].rows(), 1010u);
    // 1200: 200 left (20 %) are.
    const std::vector<io::CsvTable> two = pieces_of(write("rest2.csv", rows_text(1200, true)), 1000, {4096, 512, 2});
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[1].rows(), 201u);
    // No piece size: the whole file, as read_csv.
    expect_rows(pieces_of(write("whole.csv", rows_text(1200, true)), 0).front(), 1200);
}

TEST(CsvPieces, AnErrorInALaterPieceNamesItsLineInTheFile) {
    std::string text = rows_text(1501, true);
    const std::size_t at = text.find(",750.250000") + 1;  // row 750: line 752
    text.replace(at, 3, "7x0");
    const std::string path = write("bad_piece.csv", text);
    for (const auto& chunking : kChunkings) {
        try {
            (void)pieces_of(path, 100, chunking);
            ADD_FAILURE() << "no error";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), path + ":752: column 'a': expected a number, got '7x0.250000'");
        }
    }
}

TEST(CsvPieces, AReaderResumedAtAPositionReadsTheSamePiecesOn) {
    const std::string path = write("resume.csv", rows_text(1501, true));
    io::CsvPieceReader reader(path, {97, 31, 3});
    reader.set_piece_rows(400);
    io::CsvTable first;
    ASSERT_TRUE(reader.next(first));
    const io::CsvPosition after_first = reader.position();
    io::CsvPieceReader resumed(path, {4096, 512, 2}, {}, &after_first);
    resumed.set_piece_rows(400);
    for (io::CsvTable a, b; reader.next(a);) {
        ASSERT_TRUE(resumed.next(b));
        ASSERT_EQ(a.rows(), b.rows());
        ASSERT_EQ(a.line_of_row(0), b.line_of_row(0));
        EXPECT_EQ(a.column("a"), b.column("a"));
        EXPECT_EQ(a.column("t"), b.column("t"));
    }
    io::CsvTable none;
    EXPECT_FALSE(resumed.next(none));
    EXPECT_TRUE(resumed.at_end());
}

}  // namespace
