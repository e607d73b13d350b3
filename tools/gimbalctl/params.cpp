#include "params.hpp"

#include "numbers.hpp"

namespace gimbalctl {

CLI::Option* Params::number(const std::string& names, const std::string& key,
                            const std::string& description) {
    std::string& text = strings_.emplace_back();
    CLI::Option* option = app_->add_option(names, text, description)->check(number_check());
    option->type_name("NUMBER");
    custom(key, option, [&text] { return number_json(text); });
    return option;
}

CLI::Option* Params::integer(const std::string& names, const std::string& key,
                             const std::string& description) {
    std::int64_t& value = integers_.emplace_back();
    CLI::Option* option = app_->add_option(names, value, description);
    option->type_name("INTEGER");
    custom(key, option, [&value] { return Json(value); });
    return option;
}

CLI::Option* Params::numbers(const std::string& names, const std::string& key, std::size_t count,
                             const std::string& description) {
    std::vector<std::string>& texts = string_lists_.emplace_back();
    CLI::Option* option = app_->add_option(names, texts, description)->check(number_check());
    option->expected(static_cast<int>(count));
    option->type_name("NUMBER");
    custom(key, option, [&texts] {
        Json array = Json::array();
        for (const std::string& text : texts) array.push_back(number_json(text));
        return array;
    });
    return option;
}

CLI::Option* Params::text(const std::string& names, const std::string& key,
                          const std::string& description) {
    std::string& value = strings_.emplace_back();
    CLI::Option* option = app_->add_option(names, value, description);
    option->type_name("TEXT");
    custom(key, option, [&value] { return Json(value); });
    return option;
}

CLI::Option* Params::names(const std::string& names, const std::string& key,
                           const std::string& description) {
    std::vector<std::string>& value = string_lists_.emplace_back();
    CLI::Option* option = app_->add_option(names, value, description);
    option->type_name("NAME,...")->delimiter(',');
    custom(key, option, [&value] { return Json(value); });
    return option;
}

CLI::Option* Params::flag(const std::string& names, const std::string& key,
                          const std::string& description, bool always) {
    bool& value = bools_.emplace_back(false);
    CLI::Option* option = app_->add_flag(names, value, description);
    custom(
        key, option, [&value] { return Json(value); }, always);
    return option;
}

void Params::custom(const std::string& key, CLI::Option* option, std::function<Json()> value,
                    bool always) {
    // The key in the help text lets script writers map options to the contract.
    option->description(option->get_description() + " (JSON \"" + key + "\")");
    entries_.push_back(Entry{key, option, std::move(value), always});
}

Json Params::json() const {
    for (const auto& check : checks_) check();
    Json params = Json::object();
    for (const Entry& entry : entries_) {
        if (entry.always || entry.option->count() > 0) params[entry.key] = entry.value();
    }
    return params;
}

}  // namespace gimbalctl
