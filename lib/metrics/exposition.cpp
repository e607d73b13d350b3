#include "metrics/exposition.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace gimbal::metrics {

std::string_view to_string(Type type) {
    switch (type) {
        case Type::counter:
            return "counter";
        case Type::gauge:
            return "gauge";
        case Type::histogram:
            return "histogram";
    }
    return "untyped";
}

std::string escape_label_value(std::string_view value) {
    std::string out;
    out.reserve(value.size());
    for (char c : value) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '"')
            out += "\\\"";
        else if (c == '\n')
            out += "\\n";
        else
            out += c;
    }
    return out;
}

std::string escape_help(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '\n')
            out += "\\n";
        else
            out += c;
    }
    return out;
}

std::string format_value(double value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
    std::array<char, 64> buffer{};
    // Shortest round-trip form: 3 -> "3", 0.25 -> "0.25", 1e-05 -> "1e-05".
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

namespace {

bool name_char(char c, bool first, bool colon) {
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    if (alpha || (colon && c == ':')) return true;
    return !first && c >= '0' && c <= '9';
}

bool valid_name(std::string_view name, bool colon) {
    if (name.empty()) return false;
    for (std::size_t i = 0; i < name.size(); ++i)
        if (!name_char(name[i], i == 0, colon)) return false;
    return true;
}

}  // namespace

bool valid_metric_name(std::string_view name) {
    return valid_name(name, true);
}

bool valid_label_name(std::string_view name) {
    return valid_name(name, false) && name.substr(0, 2) != "__";
}

void Exposition::family(std::string_view name, Type type, std::string_view help) {
    if (!valid_metric_name(name))
        throw std::invalid_argument("invalid metric name: " + std::string(name));
    current_ = name;
    type_ = type;
    out_ += "# HELP ";
    out_ += name;
    out_ += ' ';
    out_ += escape_help(help);
    out_ += "\n# TYPE ";
    out_ += name;
    out_ += ' ';
    out_ += to_string(type);
    out_ += '\n';
}

void Exposition::line(std::string_view name, const Labels& labels, double value,
                      const std::pair<std::string, std::string>* extra) {
    out_ += name;
    if (!labels.empty() || extra != nullptr) {
        out_ += '{';
        bool first = true;
        auto label = [&](const std::string& key, const std::string& val) {
            if (!valid_label_name(key)) throw std::invalid_argument("invalid label name: " + key);
            if (!first) out_ += ',';
            first = false;
            out_ += key;
            out_ += "=\"";
            out_ += escape_label_value(val);
            out_ += '"';
        };
        for (const auto& [key, val] : labels) label(key, val);
        if (extra != nullptr) label(extra->first, extra->second);
        out_ += '}';
    }
    out_ += ' ';
    out_ += format_value(value);
    out_ += '\n';
}

void Exposition::sample(const Labels& labels, double value) {
    if (current_.empty()) throw std::logic_error("sample before family");
    if (type_ == Type::histogram) throw std::logic_error("use histogram() for a histogram");
    line(current_, labels, value);
}

void Exposition::histogram(const Labels& labels, const Histogram& h) {
    if (type_ != Type::histogram) throw std::logic_error("histogram() outside a histogram family");
    const std::string bucket = current_ + "_bucket";
    for (std::size_t i = 0; i < h.bounds().size(); ++i) {
        const std::pair<std::string, std::string> le{"le", format_value(h.bounds()[i])};
        line(bucket, labels, static_cast<double>(h.cumulative(i)), &le);
    }
    const std::pair<std::string, std::string> inf{"le", "+Inf"};
    line(bucket, labels, static_cast<double>(h.count()), &inf);
    line(current_ + "_sum", labels, h.sum());
    line(current_ + "_count", labels, static_cast<double>(h.count()));
}

}  // namespace gimbal::metrics
