#include "mesh/output_guard.h"

#include "mesh/error.h"

#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <system_error>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::mutex& inputs_mutex() {
    static std::mutex m;
    return m;
}
std::set<fs::path>& protected_inputs() {
    static std::set<fs::path> inputs;
    return inputs;
}

// Symbolic links of the existing part resolved, so "d/../d/x" and a link to "d" name one place.
fs::path resolved(const fs::path& path) {
    std::error_code ec;
    fs::path c = fs::weakly_canonical(path, ec);
    if (ec) c = fs::absolute(path, ec).lexically_normal();
    if (c.has_filename() || c == c.root_path()) return c;
    return c.parent_path();  // "d/" → "d"
}

// Whether `inner` lies strictly inside `outer` (component-wise).
bool strictly_inside(const fs::path& inner, const fs::path& outer) {
    auto i = inner.begin();
    for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
        if (i == inner.end() || *i != *o) return false;
    return i != inner.end();
}

bool same_file(const fs::path& a, const fs::path& b) {
    if (a == b) return true;
    std::error_code ec;
    return fs::equivalent(a, b, ec) && !ec;  // hard links, bind mounts
}

void check_one(const fs::path& output, const fs::path& out, const fs::path& input) {
    const fs::path in = resolved(input);
    const char* relation = same_file(out, in)         ? "is"
                           : strictly_inside(in, out) ? "contains"
                           : strictly_inside(out, in) ? "lies inside"
                                                      : nullptr;
    if (relation)
        throw InputError("output \"" + output.string() + "\" " + relation + " the input \"" +
                         input.string() +
                         "\"; expected an output apart from every input (nothing was written)");
}

// The value of `key` in a text header ("Key = value" or "key: value"), or empty.
std::string header_value(const fs::path& header, const std::string& key, char separator) {
    std::ifstream in(header);
    std::string line;
    for (int n = 0; n < 200 && std::getline(in, line); ++n) {
        if (line.size() <= key.size() || line.compare(0, key.size(), key) != 0) continue;
        const auto at = line.find(separator, key.size());
        if (at == std::string::npos) continue;
        std::string v = line.substr(at + 1);
        const auto not_space = [](unsigned char c) { return std::isspace(c) == 0; };
        v.erase(v.begin(), std::find_if(v.begin(), v.end(), not_space));
        v.erase(std::find_if(v.rbegin(), v.rend(), not_space).base(), v.end());
        return v;
    }
    return {};
}

std::string lower_name(const fs::path& path) {
    std::string name = path.filename().string();
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return name;
}

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The folder `output` goes into, as the user wrote it ("." for a bare file name); a trailing
// separator ("atlas/") names the folder itself, whose parent is meant.
fs::path folder_of(const fs::path& output) {
    fs::path p = output;
    if (!p.has_filename()) p = p.parent_path();
    const fs::path parent = p.parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

bool is_writable_folder(const fs::path& folder) {
    // note: W_OK and X_OK: a file is made in a folder one may write and enter.
    return ::access(folder.c_str(), W_OK | X_OK) == 0;
}

[[noreturn]] void refuse_folder(const fs::path& output, const std::string& found,
                                const std::string& expected) {
    throw InputError("output \"" + output.string() + "\": " + found + "; expected " + expected +
                     " (nothing was written)");
}

}  // namespace

void protect_input(const fs::path& path) {
    if (path.empty()) return;
    std::lock_guard lock(inputs_mutex());
    protected_inputs().insert(resolved(path));
}

namespace {

// note: a header names at most this many data files (one per slice); more is a runaway pattern
// ("%d 1 2000000000 1"), which the volume reader refuses anyway.
constexpr long kMaxDataFiles = 100000;

// One number put into a slice pattern's single conversion (%d, %i, %u with an optional
// zero flag and width; %% is a literal %). Empty when the pattern is not of that form: the
// pattern is the user's text and never reaches printf.
std::string format_slice(const std::string& pattern, long number) {
    std::string out;
    int conversions = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out += '%';
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        int width = 0;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) &&
               width < 100)
            width = 10 * width + (pattern[j++] - '0');
        if (j >= pattern.size() || (pattern[j] != 'd' && pattern[j] != 'i' && pattern[j] != 'u') ||
            ++conversions > 1)
            return {};
        std::string digits = std::to_string(number < 0 ? -number : number);
        if (number < 0) digits.insert(0, "-");
        if (static_cast<int>(digits.size()) < width)
            digits.insert(0, static_cast<std::size_t>(width) - digits.size(), zero ? '0' : ' ');
        out += digits;
        i = j;
    }
    return conversions == 1 ? out : std::string{};
}

// The lines of a header after the one that starts with `key` (a LIST's file names).
std::vector<std::string> lines_after(const fs::path& header, const std::string& key) {
    std::ifstream in(header);
    std::string line;
    std::vector<std::string> names;
    bool after = false;
    while (std::getline(in, line) && static_cast<long>(names.size()) < kMaxDataFiles) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (after) {
            if (!line.empty() && line[0] != '#') names.push_back(line);
        } else if (line.compare(0, key.size(), key) == 0) {
            after = true;
        }
    }
    return names;
}

// The data files a header's value names: one file, a LIST (the lines after the key), or a
// slice pattern "FORMAT MIN MAX STEP [SUBDIM]" (MetaImage and NRRD spell it alike).
std::vector<fs::path> data_files(const fs::path& header, const std::string& key,
                                 const std::string& value) {
    std::vector<fs::path> files;
    const fs::path dir = header.parent_path();
    const auto local = [&](const std::string& name) {
        const fs::path p(name);
        return p.is_absolute() ? p : dir / p;
    };
    if (value.empty() || value == "LOCAL") return files;
    if (value.rfind("LIST", 0) == 0) {
        for (const std::string& name : lines_after(header, key)) files.push_back(local(name));
        return files;
    }
    std::istringstream words(value);
    std::string format;
    long first = 0, last = 0, step = 0;
    words >> format;
    if ((words >> first >> last >> step) && step != 0 && format.find('%') != std::string::npos) {
        const long count = (last - first) / step + 1;
        if (count <= 0 || count > kMaxDataFiles) return files;
        for (long n = 0; n < count; ++n) {
            const std::string name = format_slice(format, first + n * step);
            if (name.empty()) break;
            files.push_back(local(name));
        }
        return files;
    }
    files.push_back(local(value));
    return files;
}

}  // namespace

std::vector<fs::path> input_files(const fs::path& path) {
    std::vector<fs::path> files{path};
    const std::string name = lower_name(path);
    std::vector<fs::path> data;
    if (ends_with(name, ".mhd")) {
        data = data_files(path, "ElementDataFile", header_value(path, "ElementDataFile", '='));
    } else if (ends_with(name, ".nhdr")) {
        std::string value = header_value(path, "data file", ':');
        const char* key = "data file";
        if (value.empty()) {
            value = header_value(path, "datafile", ':');
            key = "datafile";
        }
        data = data_files(path, key, value);
    }
    files.insert(files.end(), data.begin(), data.end());
    return files;
}

std::vector<fs::path> output_files(const fs::path& path) {
    std::vector<fs::path> files{path};
    const std::string name = lower_name(path);
    if (ends_with(name, ".mhd") || ends_with(name, ".nhdr")) {
        fs::path stem = path;
        for (const char* ext : {".raw", ".zraw", ".raw.gz"})
            files.push_back(stem.replace_extension(ext));
    }
    return files;
}

void refuse_output_over_inputs(const fs::path& output, std::span<const fs::path> inputs) {
    if (output.empty()) return;
    const fs::path out = resolved(output);
    for (const fs::path& input : inputs)
        if (!input.empty()) check_one(output, out, input);
    std::vector<fs::path> registered;
    {
        std::lock_guard lock(inputs_mutex());
        registered.assign(protected_inputs().begin(), protected_inputs().end());
    }
    for (const fs::path& input : registered) check_one(output, out, input);
}

void check_output_folder(const fs::path& output, OutputParent parent) {
    if (output.empty()) return;
    const fs::path folder = folder_of(output);
    std::error_code ec;
    const fs::file_status status = fs::status(folder, ec);
    if (fs::is_directory(status)) {
        if (!is_writable_folder(folder))
            refuse_folder(output, "folder \"" + folder.string() + "\" is not writable",
                          "a folder this user may write into");
        return;
    }
    if (fs::exists(status))
        refuse_folder(output, "\"" + folder.string() + "\" is a file, not a folder",
                      "a folder to write into");
    if (parent == OutputParent::MustExist)
        refuse_folder(output, "folder \"" + folder.string() + "\" does not exist",
                      "an existing folder to write into (make it first)");
    // The command makes the missing folders: the nearest one that exists must take them.
    fs::path existing = fs::absolute(folder, ec).lexically_normal();
    while (existing.has_relative_path() && !fs::exists(existing, ec))
        existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        refuse_folder(output,
                      "folder \"" + folder.string() + "\" cannot be made: \"" + existing.string() +
                          "\" is a file, not a folder",
                      "a folder to write into");
    if (!is_writable_folder(existing))
        refuse_folder(output,
                      "folder \"" + folder.string() + "\" cannot be made: \"" + existing.string() +
                          "\" is not writable",
                      "a folder this user may write into");
}

void guard_outputs(std::initializer_list<fs::path> outputs, std::initializer_list<fs::path> inputs,
                   OutputParent parent) {
    std::vector<fs::path> all;
    for (const fs::path& input : inputs)
        if (!input.empty())
            for (fs::path& f : input_files(input)) all.push_back(std::move(f));
    for (const fs::path& output : outputs)
        if (!output.empty())
            for (const fs::path& f : output_files(output)) refuse_output_over_inputs(f, all);
    for (const fs::path& output : outputs) check_output_folder(output, parent);
    for (const fs::path& input : all) protect_input(input);
}

}  // namespace glint
