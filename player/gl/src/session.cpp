#include "gl/session.h"

namespace gl {

const Program* ProgramCache::get(std::initializer_list<Stage> stages, const std::string& defines, std::string& error) {
  std::string key;
  for (const Stage& stage : stages) key.append(stage.file).push_back('+');
  key += defines;
  if (const auto found = programs_.find(key); found != programs_.end()) return &found->second;
  std::vector<StageSource> sources;
  if (!stage_sources(stages, defines, sources, error)) return nullptr;
  return add(std::move(key), sources, error);
}

const Program* ProgramCache::get(const std::vector<StageSource>& sources, std::string& error) {
  std::string key;
  for (const StageSource& stage : sources) key.append(stage.text).push_back('\0');
  if (const auto found = programs_.find(key); found != programs_.end()) return &found->second;
  return add(std::move(key), sources, error);
}

const Program* ProgramCache::add(std::string key, const std::vector<StageSource>& sources, std::string& error) {
  Program program = store_ ? store_->load(sources) : Program();
  if (!program) {
    program = link_program(sources, error, store_ != nullptr);
    if (!program) return nullptr;
    ++compiled_;
    std::string problem;
    if (store_ && !store_->save(sources, program, problem) && store_problem_.empty()) store_problem_ = problem;
  }
  return &programs_.emplace(std::move(key), std::move(program)).first->second;
}

std::unique_ptr<Session> Session::open(const platform::Options& options, std::string& error, bool debug_log) {
  std::unique_ptr<Session> session(new Session());
  session->platform_ = platform::create(options, error);
  if (!session->platform_ || !load(*session->platform_, error)) return nullptr;
  session->caps_ = query_caps();
  install_debug_log(session->caps_, debug_log);
  return session;
}

}  // namespace gl
