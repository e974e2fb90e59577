// SPDX-License-Identifier: MIT
#pragma once
// One idiom for every YAML file jacobid reads (firmware configs, robot descriptions, log formats): a
// YamlSection wraps one mapping, reads typed fields with their unit in the message, remembers which keys
// were read, and reject_unknown() then refuses a key nobody read, a repeated key and a list used as a key.
// Every message is one line, "file:line:column: path.key: what was expected", thrown as `Error` (the
// caller's exception type: the firmware's ConfigError, the host tools' InputError), so that a user's typo
// is named where it is. Header-only (yaml-cpp and fmt), shared by firmware/ and host-tools/.
#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace jacobid::yaml {

// "file:line:column" of a node, or the file alone when the node has no position.
inline std::string where(const std::string& source, const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    return m.is_null() ? source : fmt::format("{}:{}:{}", source, m.line + 1, m.column + 1);
}

// Parses YAML text; a syntax error becomes Error("file:line:column: invalid YAML: ...").
template <typename Error>
YAML::Node load(const std::string& text, const std::string& source) {
    try {
        return YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw Error(fmt::format("{}:{}:{}: invalid YAML: {}", source, e.mark.line + 1, e.mark.column + 1, e.msg));
    }
}

template <typename Error>
class YamlSection {
public:
    // `path` is how messages name this mapping ("" for the top level, "joints[0]", "friction", ...).
    YamlSection(std::string source, const YAML::Node& node, std::string path)
        : source_(std::move(source)), node_(node), path_(std::move(path)) {
        if (!node_.IsMap()) fail(node_, "", "must be a mapping (key: value)");
    }

    [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& message) const {
        throw Error(fmt::format("{}: {}: {}", where(source_, at), qualified(key), message));
    }
    // At the key's value when it is there, else at this mapping.
    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        const YAML::Node n = node_[key];
        fail(n.IsDefined() ? n : node_, key, message);
    }
    std::string qualified(const std::string& key) const {
        if (key.empty()) return path_.empty() ? "(top level)" : path_;
        return path_.empty() ? key : path_ + "." + key;
    }
    const std::string& source() const { return source_; }
    const YAML::Node& node() const { return node_; }

    bool has(const std::string& key) const { return node_[key].IsDefined() && !node_[key].IsNull(); }
    // The raw node (marked as read).
    YAML::Node get(const std::string& key) {
        used_.push_back(key);
        return node_[key];
    }
    void mark_used(const std::string& key) { used_.push_back(key); }

    // A nested mapping, named "path.key" in messages.
    YamlSection child(const std::string& key) {
        used_.push_back(key);
        if (!has(key)) fail(node_, key, "missing (required)");
        return YamlSection(source_, node_[key], qualified(key));
    }
    // A list (marked as read); fails unless it is a list of min..max entries.
    YAML::Node list(const std::string& key, std::size_t min_size, std::size_t max_size, const std::string& of) {
        used_.push_back(key);
        const YAML::Node n = node_[key];
        if (!n.IsSequence() || n.size() < min_size || n.size() > max_size) {
            fail(key, min_size == max_size ? fmt::format("must be a list of {} {}", min_size, of)
                                           : fmt::format("must be a list of {} to {} {}", min_size, max_size, of));
        }
        return n;
    }

    template <typename T>
    T scalar(const std::string& key, const T& fallback, const char* what) {
        used_.push_back(key);
        const YAML::Node n = node_[key];
        if (!n.IsDefined() || n.IsNull()) return fallback;
        return element<T>(n, key, what);
    }
    // One entry of a list or a value given by node, typed, with the message naming `key`.
    template <typename T>
    T element(const YAML::Node& n, const std::string& key, const char* what) const {
        if (!n.IsScalar()) fail(n, key, fmt::format("expected {}", what));
        try {
            return n.as<T>();
        } catch (const YAML::Exception&) {
            fail(n, key, fmt::format("expected {}, got '{}'", what, n.Scalar()));
        }
    }
    double number_element(const YAML::Node& n, const std::string& key, const std::string& unit = "") const {
        const double v = element<double>(n, key, "a number");
        if (!std::isfinite(v)) fail(n, key, "must be a finite number" + in(unit));
        return v;
    }

    // A finite number; `fallback` (returned when the key is absent) may be infinite, e.g. "no limit".
    double number(const std::string& key, double fallback, const std::string& unit = "") {
        used_.push_back(key);
        if (!has(key)) return fallback;
        return number_element(node_[key], key, unit);
    }
    double positive(const std::string& key, double fallback, const std::string& unit = "") {
        const double v = number(key, fallback, unit);
        if (!(v > 0.0)) fail(key, "must be > 0" + in(unit));
        return v;
    }
    long integer(const std::string& key, long fallback, long lo, long hi) {
        const long v = scalar<long>(key, fallback, "an integer");
        if (v < lo || v > hi) fail(key, fmt::format("must be an integer in {}..{}", lo, hi));
        return v;
    }
    bool boolean(const std::string& key, bool fallback) { return scalar<bool>(key, fallback, "true or false"); }
    std::string text(const std::string& key, const std::string& fallback) { return scalar<std::string>(key, fallback, "a string"); }
    std::string required_text(const std::string& key) {
        if (!has(key)) fail(node_, key, "missing (required)");
        return text(key, "");
    }
    std::string choice(const std::string& key, const std::string& fallback, std::initializer_list<const char*> options) {
        return choose(key, fallback, options);
    }
    // Options known only at run time (e.g. the device profiles of hal/profile_registry.hpp).
    std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& options) {
        return choose(key, fallback, options);
    }
    // [lo, hi] with lo < hi.
    std::pair<double, double> range(const std::string& key, std::pair<double, double> fallback, const std::string& unit = "") {
        used_.push_back(key);
        if (!has(key)) return fallback;
        const YAML::Node n = node_[key];
        if (!n.IsSequence() || n.size() != 2) fail(n, key, "expected [min, max]" + in(unit));
        const double lo = number_element(n[0], key, unit), hi = number_element(n[1], key, unit);
        if (!(lo < hi)) fail(n, key, fmt::format("need min < max, got [{}, {}]", lo, hi));
        return {lo, hi};
    }

    // Call after reading every known key.
    void reject_unknown() const {
        // yaml-cpp keeps both entries of a repeated key and a lookup returns the first one: an error here.
        std::vector<std::string> seen;
        for (const auto& kv : node_) {
            if (!kv.first.IsScalar()) fail(kv.first, "", "expected a key name, found a list or map used as a key");
            const std::string key = kv.first.Scalar();
            for (const auto& s : seen) {
                if (s == key) fail(kv.first, key, "appears twice");
            }
            seen.push_back(key);
        }
        for (const auto& kv : node_) {
            const std::string key = kv.first.Scalar();
            if (!is_used(key)) fail(kv.first, key, "unknown key (known: " + known_keys() + ")");
        }
    }

private:
    template <typename Options>
    std::string choose(const std::string& key, const std::string& fallback, const Options& options) {
        const std::string v = text(key, fallback);
        std::string all;
        for (const auto& o : options) {
            if (v == o) return v;
            all += (all.empty() ? "" : ", ") + std::string(o);
        }
        fail(key, fmt::format("'{}' is not one of: {}", v, all));
    }
    static std::string in(const std::string& unit) { return unit.empty() ? std::string() : " (" + unit + ")"; }
    bool is_used(const std::string& key) const {
        for (const auto& u : used_) {
            if (u == key) return true;
        }
        return false;
    }
    std::string known_keys() const {
        std::vector<std::string> keys;
        for (const auto& u : used_) {
            if (!std::count(keys.begin(), keys.end(), u)) keys.push_back(u);
        }
        std::sort(keys.begin(), keys.end());
        std::string all;
        for (const auto& k : keys) all += (all.empty() ? "" : ", ") + k;
        return all;
    }

    std::string source_;
    YAML::Node node_;
    std::string path_;
    std::vector<std::string> used_;
};

}  // namespace jacobid::yaml
