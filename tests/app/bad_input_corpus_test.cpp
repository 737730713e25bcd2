// The bad-input corpus, tests/data/bad/: every case ends with its documented
// exit status and one line on stderr — never a crash, a hang, an absurd
// allocation, more than one line, or a file left in the output folder. The
// cases and what they must print are the table in tests/data/bad/README.md,
// read here, so the README is the one source of truth.

#include <sys/wait.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

fs::path corpusDir() { return test::sourceDir() / "tests/data/bad"; }

// ------------------------------------------------------------------ the table

struct BadCase {
    std::string name;     // the case's folder
    std::string command;  // arguments of strahl, $OUT = the scratch output folder
    int status = -1;
    std::string stderrPattern;  // the one line strahl prints; "…" matches any text
};

// Test names carry the case name; gtest need not dump the struct's bytes.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

std::string trim(const std::string& s) {
    const size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The cells of a Markdown table row: split at '|' but not at "\|", trimmed,
// with the backticks of a code span removed.
std::vector<std::string> cells(const std::string& row) {
    std::vector<std::string> out;
    std::string cell;
    for (size_t i = 0; i < row.size(); ++i) {
        if (row[i] == '\\' && i + 1 < row.size() && row[i + 1] == '|') {
            cell += '|';
            ++i;
        } else if (row[i] == '|') {
            out.push_back(cell);
            cell.clear();
        } else {
            cell += row[i];
        }
    }
    out.push_back(cell);
    // A row starts and ends with '|': drop the empty text outside them.
    if (!out.empty() && trim(out.front()).empty()) out.erase(out.begin());
    if (!out.empty() && trim(out.back()).empty()) out.pop_back();
    for (std::string& c : out) {
        c = trim(c);
        if (c.size() >= 2 && c.front() == '`' && c.back() == '`') c = c.substr(1, c.size() - 2);
    }
    return out;
}

// The rows of the README table whose header has the columns case, command,
// exit and stderr (in any order, among others). Empty if there is none.
std::vector<BadCase> readCorpusTable() {
    std::istringstream readme(test::readFile(corpusDir() / "README.md"));
    std::map<std::string, size_t> column;
    std::vector<BadCase> cases;
    bool inTable = false;
    for (std::string line; std::getline(readme, line);) {
        line = trim(line);
        if (line.empty() || line[0] != '|') {
            if (inTable) break;
            continue;
        }
        const std::vector<std::string> row = cells(line);
        if (!inTable) {
            if (row.empty() || row[0] != "case") continue;
            for (size_t i = 0; i < row.size(); ++i) column[row[i]] = i;
            inTable = column.count("command") && column.count("exit") && column.count("stderr");
            continue;
        }
        if (row[0].find_first_not_of("-: ") == std::string::npos) continue;  // |---|---|
        BadCase c;
        const auto at = [&](const char* name) {
            const size_t i = column[name];
            return i < row.size() ? row[i] : std::string();
        };
        c.name = at("case");
        c.command = at("command");
        c.status = std::atoi(at("exit").c_str());
        c.stderrPattern = at("stderr");
        cases.push_back(c);
    }
    return cases;
}

// ------------------------------------------------------------------ helpers

const std::string kAnyText = "\xE2\x80\xA6";  // "…" in the README's patterns

// Whether `text` matches `pattern`, in which "…" stands for any text.
bool matchesPattern(const std::string& text, const std::string& pattern) {
    std::vector<std::string> pieces;
    for (size_t start = 0;;) {
        const size_t any = pattern.find(kAnyText, start);
        pieces.push_back(pattern.substr(start, any - start));
        if (any == std::string::npos) break;
        start = any + kAnyText.size();
    }
    if (pieces.size() == 1) return text == pattern;
    if (text.compare(0, pieces.front().size(), pieces.front()) != 0) return false;
    size_t pos = pieces.front().size();
    for (size_t i = 1; i + 1 < pieces.size(); ++i) {
        pos = text.find(pieces[i], pos);
        if (pos == std::string::npos) return false;
        pos += pieces[i].size();
    }
    const std::string& last = pieces.back();
    return text.size() >= pos + last.size() &&
           text.compare(text.size() - last.size(), last.size(), last) == 0;
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::vector<std::string> splitWords(const std::string& text) {
    std::vector<std::string> words;
    std::istringstream in(text);
    for (std::string word; in >> word;) words.push_back(word);
    return words;
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
    for (size_t pos = text.find(from); pos != std::string::npos;
         pos = text.find(from, pos + to.size()))
        text.replace(pos, from.size(), to);
    return text;
}

// Every file below `dir` with its size and modification time.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        std::ostringstream state;
        state << (entry.is_regular_file() ? entry.file_size() : 0) << " "
              << entry.last_write_time().time_since_epoch().count();
        files[fs::relative(entry.path(), dir).string()] = state.str();
    }
    return files;
}

std::vector<std::string> listDir(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Sanitizers reserve terabytes of address space; the memory limit is for the
// plain builds.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

struct CorpusRun {
    int status = -1;      // the exit status, or -1 when killed by a signal
    std::string how;      // how it ended, for failure messages
    std::string out, err;
};

// Runs `strahl <args>` in `dir`: a hang ends after 120 s (status 124), and an
// allocation beyond 16 GiB of address space fails (as "out of memory", not the
// expected message) instead of swapping the machine to death. A lying header
// asks for far more: 10^12 vertices are 12 TB. Few malloc arenas keep the
// address space of many threads small; $OCIO must not change the outcome.
CorpusRun runIn(const fs::path& dir, const std::string& args, const fs::path& scratch) {
    const fs::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
    std::string command = "cd '" + dir.string() + "' && ";
    if (!kSanitized) command += "ulimit -v 16777216 && ";
    command += "exec env -u OCIO MALLOC_ARENA_MAX=4 timeout -k 5 120 " +
               std::string(STRAHL_BINARY) + " " + args + " >'" + out.string() + "' 2>'" +
               err.string() + "'";
    const int raw = std::system(command.c_str());
    CorpusRun r;
    if (raw != -1 && WIFEXITED(raw)) {
        r.status = WEXITSTATUS(raw);
        r.how = r.status == 124 ? "timed out after 120 s (a hang?)"
                                : "exit status " + std::to_string(r.status);
    } else {
        r.how = raw != -1 && WIFSIGNALED(raw) ? "killed by signal " + std::to_string(WTERMSIG(raw))
                                              : "could not be run";
    }
    r.out = test::readFile(out);
    r.err = test::readFile(err);
    return r;
}

// ------------------------------------------------------------------ the tests

class BadInputCorpus : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInputCorpus, EndsAsDocumented) {
    const BadCase& c = GetParam();
    const fs::path caseDir = corpusDir() / c.name;
    ASSERT_TRUE(fs::is_directory(caseDir)) << caseDir;
    const fs::path scratch = test::scratchDir("bad-input-" + c.name);
    const fs::path outDir = scratch / "out";
    fs::create_directories(outDir);
    const std::string args = replaceAll(c.command, "$OUT", "'" + outDir.string() + "'");
    const auto before = snapshot(caseDir);

    const CorpusRun r = runIn(caseDir, args, scratch);
    const std::string context = "strahl " + args + "\nin " + caseDir.string() + "\n" + r.how +
                                ", stderr:\n" + r.err;
    EXPECT_EQ(r.status, c.status) << context;

    const std::vector<std::string> lines = splitLines(r.err);
    if (c.status != 0) {
        // One line: the error, naming the file (or the option) at fault.
        ASSERT_EQ(lines.size(), 1u) << "expected exactly one line on stderr\n" << context;
        EXPECT_EQ(r.err.back(), '\n') << context;
        EXPECT_EQ(lines[0].rfind("strahl: error: ", 0), 0u) << context;
        EXPECT_TRUE(matchesPattern(lines[0], c.stderrPattern))
            << "expected: " << c.stderrPattern << "\n" << context;
        bool namesCulprit = false;
        for (const std::string& file : listDir(caseDir))
            namesCulprit = namesCulprit || test::contains(lines[0], file);
        for (const std::string& word : splitWords(c.command)) {
            const bool option = word.rfind("--", 0) == 0 && c.status == 2;
            const std::string name = fs::path(word).filename().string();
            if (option || (c.status == 1 && name.find('.') != std::string::npos))
                namesCulprit = namesCulprit || test::contains(lines[0], option ? word : name);
        }
        EXPECT_TRUE(namesCulprit) << "the message names no file or option of the case\n" << context;
        EXPECT_EQ(r.out, "") << "nothing on stdout\n" << context;
        EXPECT_EQ(listDir(outDir), std::vector<std::string>{})
            << "an output or temporary file was left behind\n" << context;
    } else {
        // Rendered, with exactly one "strahl: " line: the warning.
        std::vector<std::string> own;
        for (const std::string& line : lines)
            if (line.rfind("strahl: ", 0) == 0) own.push_back(line);
        ASSERT_EQ(own.size(), 1u) << "expected exactly one warning\n" << context;
        EXPECT_EQ(own[0].rfind("strahl: warning: ", 0), 0u) << context;
        EXPECT_TRUE(matchesPattern(own[0], c.stderrPattern))
            << "expected: " << c.stderrPattern << "\n" << context;
        std::vector<std::string> images;
        const std::vector<std::string> words = splitWords(c.command);
        for (size_t i = 0; i + 1 < words.size(); ++i)
            if (words[i] == "-o" && words[i + 1].rfind("$OUT/", 0) == 0)
                images.push_back(words[i + 1].substr(5));
        std::sort(images.begin(), images.end());
        EXPECT_FALSE(images.empty()) << "a rendering case needs -o $OUT/...";
        EXPECT_EQ(listDir(outDir), images) << "the images and nothing else\n" << context;
    }
    EXPECT_EQ(snapshot(caseDir), before) << "the case folder was changed\n" << context;
    fs::remove_all(scratch);
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputCorpus, ::testing::ValuesIn(readCorpusTable()),
                         [](const auto& testInfo) { return testInfo.param.name; });

TEST(BadInputCorpusTable, CoversEveryFolderWithSmallFiles) {
    const std::vector<BadCase> cases = readCorpusTable();
    ASSERT_GE(cases.size(), 30u) << "the table in tests/data/bad/README.md was not found";
    std::set<std::string> rows;
    for (const BadCase& c : cases) {
        EXPECT_TRUE(rows.insert(c.name).second) << "two rows for " << c.name;
        EXPECT_TRUE(c.status == 0 || c.status == 1 || c.status == 2) << c.name;
        EXPECT_TRUE(c.command.find("scene.json") != std::string::npos ||
                    c.command.find("scene.xml") != std::string::npos ||
                    c.command.find("scene.pbrt") != std::string::npos)
            << c.name;
        const std::string prefix = c.status == 0 ? "strahl: warning: " : "strahl: error: ";
        EXPECT_EQ(c.stderrPattern.rfind(prefix, 0), 0u) << c.name << ": " << c.stderrPattern;
        // A gtest name: letters, digits and '_' only.
        EXPECT_EQ(c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_"),
                  std::string::npos)
            << c.name;
    }
    std::set<std::string> folders;
    for (const auto& entry : fs::directory_iterator(corpusDir())) {
        if (!entry.is_directory()) continue;
        const std::string name = entry.path().filename().string();
        folders.insert(name);
        EXPECT_TRUE(rows.count(name)) << "folder " << name << " has no row in the README table";
        EXPECT_TRUE(fs::exists(entry.path() / "scene.json") || fs::exists(entry.path() / "scene.xml") ||
                    fs::exists(entry.path() / "scene.pbrt"))
            << name;
        for (const auto& file : fs::recursive_directory_iterator(entry.path())) {
            if (file.is_regular_file()) {
                EXPECT_LT(file.file_size(), 10u * 1024u) << file.path();
            }
        }
    }
    for (const std::string& row : rows)
        EXPECT_TRUE(folders.count(row)) << "row " << row << " has no folder";
}

TEST(BadInputCorpusTable, PatternsMatchAsDocumented) {
    EXPECT_TRUE(matchesPattern("a.ply:line 3: x", "a.ply:line 3: x"));
    EXPECT_FALSE(matchesPattern("a.ply:line 3: xy", "a.ply:line 3: x"));
    EXPECT_TRUE(matchesPattern("/abs/dir/a.ply: bad", "\xE2\x80\xA6/a.ply: bad"));
    EXPECT_TRUE(matchesPattern("e: abc def", "e: \xE2\x80\xA6" "c\xE2\x80\xA6"));
    EXPECT_TRUE(matchesPattern("e: x", "e: x\xE2\x80\xA6"));
    EXPECT_FALSE(matchesPattern("e: x", "e: \xE2\x80\xA6" "x\xE2\x80\xA6y"));
    EXPECT_FALSE(matchesPattern("ab", "a\xE2\x80\xA6" "b\xE2\x80\xA6" "b"));
    EXPECT_EQ(cells("| `a` | b \\| c | 1 |"), (std::vector<std::string>{"a", "b | c", "1"}));
}

}  // namespace
}  // namespace strahl
