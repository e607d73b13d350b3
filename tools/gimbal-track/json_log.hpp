// gimbal-track's log: one JSON object per line on standard error, as gimbald's own
// (contract section 6): {"ts","level","event","msg", fields...}. gimbald reads the child's
// standard error into its journal.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

namespace gimbal_track {

enum class Level { debug, info, warn, error };
std::optional<Level> parse_level(std::string_view name);

class Log {
  public:
    explicit Log(Level level = Level::info) : level_(level) {}
    void write(Level level, std::string_view event, std::string_view msg,
               const nlohmann::json& fields = nlohmann::json::object()) const;
    void debug(std::string_view e, std::string_view m,
               const nlohmann::json& f = nlohmann::json::object()) const {
        write(Level::debug, e, m, f);
    }
    void info(std::string_view e, std::string_view m,
              const nlohmann::json& f = nlohmann::json::object()) const {
        write(Level::info, e, m, f);
    }
    void warn(std::string_view e, std::string_view m,
              const nlohmann::json& f = nlohmann::json::object()) const {
        write(Level::warn, e, m, f);
    }
    void error(std::string_view e, std::string_view m,
               const nlohmann::json& f = nlohmann::json::object()) const {
        write(Level::error, e, m, f);
    }

  private:
    Level level_;
};

}  // namespace gimbal_track
