#include "command/request_limits.hpp"

#include <string>

namespace gimbal::command {

bool nested_deeper_than(std::string_view text, std::size_t max_depth) {
    std::size_t depth = 0;
    bool in_string = false;
    bool escaped = false;
    for (const char c : text) {
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
            continue;
        }
        switch (c) {
            case '"':
                in_string = true;
                break;
            case '[':
            case '{':
                if (++depth > max_depth) return true;
                break;
            case ']':
            case '}':
                if (depth > 0) --depth;
                break;
            default:
                break;
        }
    }
    return false;
}

std::optional<Error> check_request_limits(std::string_view text) {
    if (text.size() > max_request_bytes)
        return Error{code::too_large, "the request is " + std::to_string(text.size()) +
                                          " bytes, the limit is " +
                                          std::to_string(max_request_bytes)};
    if (nested_deeper_than(text, max_json_depth))
        return Error{code::bad_json,
                     "JSON nested deeper than " + std::to_string(max_json_depth) + " levels"};
    return std::nullopt;
}

}  // namespace gimbal::command
