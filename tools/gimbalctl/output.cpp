#include "output.hpp"

#include <iostream>

#include "exit_status.hpp"

namespace gimbalctl {

std::string format_json(const Json& value, bool pretty) {
    return value.dump(pretty ? 2 : -1, ' ', false, Json::error_handler_t::replace);
}

void print_json(const Json& value, bool pretty) {
    std::cout << format_json(value, pretty) << '\n' << std::flush;
}

void print_diagnostic(const std::string& what) {
    std::cerr << "gimbalctl: " << what << '\n' << std::flush;
}

std::string format_seconds(double seconds) {
    std::string text = std::to_string(seconds);
    text.erase(text.find_last_not_of('0') + 1);
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text + " s";
}

std::string error_summary(const Json& reply) {
    std::string code = "error";
    std::string message = "(no message)";
    const auto error = reply.find("error");
    if (error != reply.end() && error->is_object()) {
        const auto code_member = error->find("code");
        if (code_member != error->end()) {
            code = code_member->is_string() ? code_member->get<std::string>()
                                            : format_json(*code_member, false);
        }
        const auto message_member = error->find("message");
        if (message_member != error->end()) {
            message = message_member->is_string() ? message_member->get<std::string>()
                                                  : format_json(*message_member, false);
        }
    }
    return code + ": " + message;
}

int report_reply(const Json& reply, bool pretty) {
    print_json(reply, pretty);
    const auto ok = reply.find("ok");
    if (ok != reply.end() && *ok == true) return exit_ok;
    print_diagnostic(error_summary(reply));
    return exit_error_reply;
}

}  // namespace gimbalctl
