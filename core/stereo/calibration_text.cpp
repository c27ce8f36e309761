// Strict reader of the calibration subset of OpenCV FileStorage YAML and XML (see
// calibration_text.hpp and docs/calibration.md).
#include "stereo/calibration_text.hpp"

#include "stereo/calibration.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

namespace gc {

namespace {

// Throws the CalibrationError of a syntax error: file, line, key (when known), what.
class Failer {
public:
    explicit Failer(const std::string& source) : source_(source) {}

    [[noreturn]] void operator()(std::size_t line, std::string_view key, const std::string& what) const
    {
        std::ostringstream msg;
        msg << "calibration file '" << source_ << "': line " << line << ": ";
        if (!key.empty()) msg << "key '" << key << "': ";
        msg << what;
        throw CalibrationError(msg.str());
    }

private:
    const std::string& source_;
};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c) || c == '-'; }

std::string_view trim(std::string_view s)
{
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
    return s;
}

bool equals_ignoring_case(std::string_view a, std::string_view b)
{
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto lower = [](char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; };
        if (lower(a[i]) != lower(b[i])) return false;
    }
    return true;
}

// Messages quote what was found; a token from a hostile file is shown cut short.
std::string quoted(std::string_view token)
{
    constexpr std::size_t kShown = 32;
    std::string s;
    s.reserve(kShown + 5);
    s.push_back('\'');
    for (char c : token.substr(0, kShown))
        s.push_back(static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f ? '?' : c);
    s.append(token.size() > kShown ? "...'" : "'");
    return s;
}

// A double-quoted text value without inner quotes, as FileStorage writes strings.
bool is_quoted_text(std::string_view token)
{
    return token.size() >= 2 && token.front() == '"' && token.back() == '"' &&
           token.substr(1, token.size() - 2).find('"') == std::string_view::npos;
}

// A decimal number as FileStorage writes one ("640", "-3.5e-07", "1.", ".Nan", "-.Inf").
std::optional<CalibrationScalar> parse_number(std::string_view token)
{
    std::string_view body = token;
    bool negative = false;
    if (!body.empty() && (body.front() == '+' || body.front() == '-')) {
        negative = body.front() == '-';
        body.remove_prefix(1);
    }
    if (equals_ignoring_case(body, ".nan")) return CalibrationScalar{std::numeric_limits<double>::quiet_NaN(), false};
    if (equals_ignoring_case(body, ".inf")) {
        const double inf = std::numeric_limits<double>::infinity();
        return CalibrationScalar{negative ? -inf : inf, false};
    }
    if (body.empty() || !(is_digit(body.front()) || body.front() == '.')) return std::nullopt;
    bool integral = true;
    for (char c : body) {
        if (c == '.' || c == 'e' || c == 'E')
            integral = false;
        else if (!is_digit(c) && c != '+' && c != '-')
            return std::nullopt;
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
    if (ec != std::errc() || end != body.data() + body.size()) return std::nullopt;
    return CalibrationScalar{negative ? -value : value, integral};
}

// A matrix node being read: its fields may come in any order, each once.
class MatrixBuilder {
public:
    MatrixBuilder(std::string key, std::size_t line, const Failer& fail)
        : key_(std::move(key)), line_(line), fail_(fail)
    {
    }

    const std::string& key() const { return key_; }
    std::size_t line() const { return line_; }

    // `field` is rows, cols, dt or data (data's values come through add_value).
    void set_field(std::string_view field, std::string_view value, std::size_t line)
    {
        if (field == "rows")
            set_dimension(rows_, field, value, line);
        else if (field == "cols")
            set_dimension(cols_, field, value, line);
        else if (field == "dt")
            set_dt(value, line);
        else if (field == "data")
            mark(has_data_, field, line);
        else
            fail_(line, key_, "unknown matrix field " + quoted(field) + " (expected rows, cols, dt and data)");
    }

    void add_value(std::string_view token, std::size_t line)
    {
        if (data_.size() == kCalibrationMaxMatrixValues)
            fail_(line, key_, "matrix data has more than " + std::to_string(kCalibrationMaxMatrixValues) + " values");
        const auto number = parse_number(token);
        if (!number) fail_(line, key_, "matrix data holds a non-number " + quoted(token));
        all_integral_ = all_integral_ && number->integral;
        data_.push_back(number->value);
    }

    CalibrationMatrix finish(std::size_t line)
    {
        if (!rows_ || !cols_ || !dt_ || !has_data_)
            fail_(line, key_, "incomplete matrix (rows, cols, dt and data are all required)");
        const std::int64_t expected = *rows_ * *cols_;
        if (expected > static_cast<std::int64_t>(kCalibrationMaxMatrixValues))
            fail_(line, key_,
                  "matrix size " + shape() + " exceeds " + std::to_string(kCalibrationMaxMatrixValues) + " values");
        if (static_cast<std::int64_t>(data_.size()) != expected)
            fail_(line, key_,
                  "matrix data has " + std::to_string(data_.size()) + " values, expected " + std::to_string(expected) +
                      " for " + shape());
        if (*dt_ != 'f' && *dt_ != 'd' && !all_integral_)
            fail_(line, key_, std::string("matrix data holds a fraction but dt is '") + *dt_ + "' (an integer type)");
        return CalibrationMatrix{static_cast<int>(*rows_), static_cast<int>(*cols_), *dt_, std::move(data_)};
    }

private:
    void mark(bool& seen, std::string_view field, std::size_t line)
    {
        if (seen) fail_(line, key_, "matrix field " + quoted(field) + " given twice");
        seen = true;
    }

    void set_dimension(std::optional<std::int64_t>& dim, std::string_view field, std::string_view value,
                       std::size_t line)
    {
        bool seen = dim.has_value();
        mark(seen, field, line);
        std::int64_t v = -1;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
        if (value.empty() || !is_digit(value.front()) || ec != std::errc() || end != value.data() + value.size() ||
            v > INT_MAX)
            fail_(line, key_, "matrix " + std::string(field) + " " + quoted(value) + " is not a non-negative integer");
        dim = v;
    }

    void set_dt(std::string_view value, std::size_t line)
    {
        bool seen = dt_.has_value();
        mark(seen, "dt", line);
        constexpr std::string_view kTypes = "ucwsifd";
        if (value.size() != 1 || kTypes.find(value.front()) == std::string_view::npos)
            fail_(line, key_,
                  "unsupported element type dt " + quoted(value) +
                      " (expected one single-channel type of u, c, w, s, i, f, d)");
        dt_ = value.front();
    }

    std::string shape() const { return std::to_string(*rows_) + "x" + std::to_string(*cols_); }

    std::string key_;
    std::size_t line_;
    const Failer& fail_;
    std::optional<std::int64_t> rows_, cols_;
    std::optional<char> dt_;
    bool has_data_ = false;
    bool all_integral_ = true;
    std::vector<double> data_;
};

void add_entry(CalibrationEntries& entries, std::string key, CalibrationEntry entry, const Failer& fail)
{
    const auto it = entries.find(key);
    if (it != entries.end())
        fail(entry.line, key, "duplicate key (first given on line " + std::to_string(it->second.line) + ")");
    entries.emplace(std::move(key), std::move(entry));
}

void check_line_lengths(std::string_view text, const Failer& fail)
{
    std::size_t line = 1, start = 0;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        if (i < text.size() && text[i] != '\n') continue;
        if (i - start > kCalibrationMaxLineBytes)
            fail(line, "", "line longer than " + std::to_string(kCalibrationMaxLineBytes) + " bytes");
        ++line;
        start = i + 1;
    }
}

// ---- YAML: line by line; a top-level "key: value" or "key: !!opencv-matrix" followed by
// the indented rows/cols/dt/data lines, data a flow sequence that may span lines.

std::string_view strip_yaml_comment(std::string_view line)
{
    for (std::size_t i = 0; i < line.size(); ++i)
        if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) return line.substr(0, i);
    return line;
}

class YamlReader {
public:
    YamlReader(const Failer& fail) : fail_(fail) {}

    CalibrationEntries read(std::string_view text)
    {
        std::size_t line_no = 0, pos = 0;
        enum class Stage { header, document_start, body } stage = Stage::header;
        while (pos < text.size()) {
            const std::size_t eol = std::min(text.find('\n', pos), text.size());
            const std::string_view raw = text.substr(pos, eol - pos);
            pos = eol + 1;
            ++line_no;
            if (stage == Stage::header) {
                const std::string_view header = trim(raw);
                if (header != "%YAML:1.0" && header != "%YAML 1.0")
                    fail_(line_no, "", "expected the header '%YAML:1.0', found " + quoted(header));
                stage = Stage::document_start;
                continue;
            }
            const std::string_view content = trim(strip_yaml_comment(raw));
            if (content.empty()) continue;
            if (stage == Stage::document_start) {
                if (content != "---") fail_(line_no, "", "expected '---' after the header, found " + quoted(content));
                stage = Stage::body;
                continue;
            }
            body_line(strip_yaml_comment(raw), line_no);
        }
        if (stage != Stage::body) fail_(line_no, "", "truncated file: no '---' document start");
        finish_matrix(line_no);
        return std::move(entries_);
    }

private:
    void body_line(std::string_view line, std::size_t line_no)
    {
        std::size_t indent = 0;
        while (indent < line.size() && (line[indent] == ' ' || line[indent] == '\t')) {
            if (line[indent] == '\t') fail_(line_no, current_key(), "tab in the indentation");
            ++indent;
        }
        const std::string_view content = trim(line);
        if (data_open_) {
            if (indent == 0) fail_(line_no, current_key(), "matrix data not closed with ']' before the next key");
            data_values(content, line_no);
            return;
        }
        if (indent == 0) {
            finish_matrix(line_no);
            top_level(content, line_no);
            return;
        }
        if (!matrix_)
            fail_(line_no, "",
                  "indented line " + quoted(content) + " outside a matrix (only !!opencv-matrix nodes may be nested)");
        const auto [field, value] = split_key(content, line_no, matrix_->key());
        matrix_->set_field(field, value, line_no);
        if (field == "data") {
            if (value.empty() || value.front() != '[')
                fail_(line_no, matrix_->key(), "matrix data must be a '[ ... ]' sequence");
            data_open_ = true;
            expect_value_ = true;
            data_values(value.substr(1), line_no);
        }
    }

    void top_level(std::string_view content, std::size_t line_no)
    {
        const auto [key, value] = split_key(content, line_no, "");
        if (value == "!!opencv-matrix") {
            matrix_.emplace(std::string(key), line_no, fail_);
            return;
        }
        if (value.empty()) fail_(line_no, key, "no value (nested nodes other than !!opencv-matrix are not supported)");
        if (is_quoted_text(value)) {
            add_entry(entries_, std::string(key),
                      CalibrationEntry{line_no, CalibrationText{std::string(value.substr(1, value.size() - 2))}},
                      fail_);
            return;
        }
        const auto number = parse_number(value);
        if (!number) fail_(line_no, key, "value " + quoted(value) + " is not a number or an !!opencv-matrix");
        add_entry(entries_, std::string(key), CalibrationEntry{line_no, *number}, fail_);
    }

    // "name: value" with a plain name; value trimmed, possibly empty.
    std::pair<std::string_view, std::string_view> split_key(std::string_view content, std::size_t line_no,
                                                            std::string_view owner)
    {
        std::size_t n = 0;
        if (!content.empty() && is_name_start(content[0]))
            while (n < content.size() && is_name_char(content[n])) ++n;
        if (n == 0 || n == content.size() || content[n] != ':' ||
            (n + 1 < content.size() && content[n + 1] != ' ' && content[n + 1] != '\t'))
            fail_(line_no, owner, "expected 'name: value', found " + quoted(content));
        return {content.substr(0, n), trim(content.substr(n + 1))};
    }

    // Values of a data sequence: numbers separated by commas, closed by ']'.
    void data_values(std::string_view s, std::size_t line_no)
    {
        std::size_t i = 0;
        while (i < s.size()) {
            const char c = s[i];
            if (is_blank(c)) {
                ++i;
            } else if (!data_open_) {
                fail_(line_no, matrix_->key(), "unexpected " + quoted(s.substr(i)) + " after the matrix data");
            } else if (c == ',') {
                if (expect_value_) fail_(line_no, matrix_->key(), "empty value in the matrix data");
                expect_value_ = true;
                ++i;
            } else if (c == ']') {
                if (expect_value_ && values_ > 0) fail_(line_no, matrix_->key(), "matrix data ends with a ','");
                data_open_ = false;
                ++i;
            } else {
                if (!expect_value_) fail_(line_no, matrix_->key(), "matrix data values must be separated by ','");
                std::size_t end = i;
                while (end < s.size() && !is_blank(s[end]) && s[end] != ',' && s[end] != ']') ++end;
                matrix_->add_value(s.substr(i, end - i), line_no);
                ++values_;
                expect_value_ = false;
                i = end;
            }
        }
    }

    void finish_matrix(std::size_t line_no)
    {
        if (data_open_) fail_(line_no, current_key(), "truncated file: matrix data not closed with ']'");
        if (!matrix_) return;
        std::string key = matrix_->key();
        const std::size_t key_line = matrix_->line();
        CalibrationMatrix m = matrix_->finish(line_no);
        matrix_.reset();
        values_ = 0;
        add_entry(entries_, std::move(key), CalibrationEntry{key_line, std::move(m)}, fail_);
    }

    std::string_view current_key() const { return matrix_ ? std::string_view(matrix_->key()) : std::string_view(); }

    const Failer& fail_;
    CalibrationEntries entries_;
    std::optional<MatrixBuilder> matrix_;
    bool data_open_ = false;
    bool expect_value_ = true;
    std::size_t values_ = 0;
};

// ---- XML: <?xml ...?> <opencv_storage> then <key>number</key> or
// <key type_id="opencv-matrix"> with <rows>, <cols>, <dt>, <data> children; comments between
// elements.

class XmlReader {
public:
    XmlReader(std::string_view text, const Failer& fail) : text_(text), fail_(fail) {}

    CalibrationEntries read()
    {
        if (!starts_with("<?xml") || pos_ + 5 >= text_.size() || !is_blank(text_[pos_ + 5]))
            fail_(line_, "", "expected the declaration '<?xml version=\"1.0\"?>'");
        skip_past("?>", "the XML declaration");
        skip_blanks_and_comments();
        expect("<opencv_storage>", "");
        while (true) {
            skip_blanks_and_comments();
            if (starts_with("</opencv_storage>")) {
                advance(std::string_view("</opencv_storage>").size());
                skip_blanks_and_comments();
                if (pos_ < text_.size()) fail_(line_, "", "content after </opencv_storage>");
                return std::move(entries_);
            }
            element();
        }
    }

private:
    void element()
    {
        const std::size_t key_line = line_;
        expect("<", "");
        const std::string key(name(""));
        skip_blanks();
        if (peek() == '>') {
            advance(1);
            const std::string_view value = trim(text_until_tag(key));
            if (is_quoted_text(value)) {
                CalibrationText text{std::string(value.substr(1, value.size() - 2))};
                close_tag(key, key);
                add_entry(entries_, key, CalibrationEntry{key_line, std::move(text)}, fail_);
                return;
            }
            const auto number = parse_number(value);
            if (!number) fail_(key_line, key, "value " + quoted(value) + " is not a number or an opencv-matrix");
            close_tag(key, key);
            add_entry(entries_, key, CalibrationEntry{key_line, *number}, fail_);
            return;
        }
        attribute(key);
        MatrixBuilder matrix(key, key_line, fail_);
        while (true) {
            skip_blanks_and_comments();
            if (starts_with("</")) break;
            const std::size_t field_line = line_;
            expect("<", key);
            const std::string_view field = name(key);
            expect(">", key);
            const std::string_view content = text_until_tag(key);
            if (field == "data") {
                matrix.set_field(field, "", field_line);
                data_values(matrix, content, field_line);
            } else {
                matrix.set_field(field, trim(content), field_line);
            }
            close_tag(field, key);
        }
        CalibrationMatrix m = matrix.finish(line_);
        close_tag(key, key);
        add_entry(entries_, key, CalibrationEntry{key_line, std::move(m)}, fail_);
    }

    // The only attribute accepted: type_id="opencv-matrix", then '>'.
    void attribute(const std::string& key)
    {
        const std::string_view attr = name(key);
        skip_blanks();
        expect("=", key);
        skip_blanks();
        const char quote = peek();
        if (quote != '"' && quote != '\'') fail_(line_, key, "attribute value not quoted");
        advance(1);
        const std::size_t end = text_.find(quote, pos_);
        if (end == std::string_view::npos) fail_(line_, key, "truncated file: attribute value not closed");
        const std::string_view value = text_.substr(pos_, end - pos_);
        if (attr != "type_id" || value != "opencv-matrix")
            fail_(line_, key,
                  "unsupported attribute " + quoted(attr) + "=" + quoted(value) +
                      " (only type_id=\"opencv-matrix\" is read)");
        advance(end + 1 - pos_);
        skip_blanks();
        expect(">", key);
    }

    void data_values(MatrixBuilder& matrix, std::string_view content, std::size_t line)
    {
        std::size_t i = 0;
        while (i < content.size()) {
            if (is_blank(content[i])) {
                line += content[i] == '\n';
                ++i;
                continue;
            }
            std::size_t end = i;
            while (end < content.size() && !is_blank(content[end])) ++end;
            matrix.add_value(content.substr(i, end - i), line);
            i = end;
        }
    }

    // Text up to the next '<' (element content never holds markup here).
    std::string_view text_until_tag(std::string_view key)
    {
        const std::size_t end = text_.find('<', pos_);
        if (end == std::string_view::npos) fail_(line_, key, "truncated file: element not closed");
        const std::string_view content = text_.substr(pos_, end - pos_);
        advance(end - pos_);
        return content;
    }

    void close_tag(std::string_view element, std::string_view key)
    {
        expect("</", key);
        const std::size_t at = line_;
        const std::string_view closing = name(key);
        if (closing != element)
            fail_(at, key,
                  "closing tag </" + std::string(closing.substr(0, 32)) + "> does not match <" + std::string(element) +
                      ">");
        skip_blanks();
        expect(">", key);
    }

    std::string_view name(std::string_view key)
    {
        const std::size_t start = pos_;
        if (pos_ < text_.size() && is_name_start(text_[pos_]))
            while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
        if (pos_ == start)
            fail_(line_, key,
                  pos_ < text_.size() ? "expected an element name, found " + quoted(text_.substr(pos_, 16))
                                      : std::string("truncated file: expected an element name"));
        return text_.substr(start, pos_ - start);
    }

    void skip_blanks()
    {
        while (pos_ < text_.size() && is_blank(text_[pos_])) advance(1);
    }

    void skip_blanks_and_comments()
    {
        while (true) {
            skip_blanks();
            if (!starts_with("<!--")) return;
            skip_past("-->", "a comment");
        }
    }

    void skip_past(std::string_view terminator, std::string_view what)
    {
        const std::size_t end = text_.find(terminator, pos_);
        if (end == std::string_view::npos) fail_(line_, "", "truncated file: " + std::string(what) + " not closed");
        advance(end + terminator.size() - pos_);
    }

    void expect(std::string_view token, std::string_view key)
    {
        if (!starts_with(token)) {
            if (pos_ >= text_.size()) fail_(line_, key, "truncated file: expected '" + std::string(token) + "'");
            fail_(line_, key, "expected '" + std::string(token) + "', found " + quoted(text_.substr(pos_, 16)));
        }
        advance(token.size());
    }

    void advance(std::size_t n)
    {
        for (std::size_t end = pos_ + n; pos_ < end; ++pos_) line_ += text_[pos_] == '\n';
    }

    bool starts_with(std::string_view s) const { return text_.substr(pos_).starts_with(s); }
    char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }

    std::string_view text_;
    const Failer& fail_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    CalibrationEntries entries_;
};

}  // namespace

CalibrationEntries read_calibration_text(std::string_view text, const std::string& source)
{
    const Failer fail(source);
    check_line_lengths(text, fail);
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // a UTF-8 byte order mark
    if (text.starts_with("%YAML")) return YamlReader(fail).read(text);
    if (text.starts_with("<?xml")) return XmlReader(text, fail).read();
    fail(1, "", "neither YAML (first line '%YAML:1.0') nor XML (first line '<?xml version=\"1.0\"?>')");
}

}  // namespace gc
