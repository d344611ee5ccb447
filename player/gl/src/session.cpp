#include "gl/session.h"

namespace gl {

const Program* ProgramCache::get(std::initializer_list<Stage> stages, const std::string& defines, std::string& error) {
  std::string key;
  for (const Stage& stage : stages) key.append(stage.file).push_back('+');
  key += defines;
  if (const auto found = programs_.find(key); found != programs_.end()) return &found->second;
  Program program = build_program(stages, defines, error);
  if (!program) return nullptr;
  ++compiled_;
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
