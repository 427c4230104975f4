// The entry points: reading and parsing files (once each), include<> (the file's
// statements spliced in place) and use<> (the file's modules and functions, in a
// scope of their own), -D definitions, and running the evaluation on a thread whose
// stack is large enough for max_stack_bytes of recursion.
#include "cellforge/csg/evaluator.h"

#include <pthread.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cellforge/csg/parser.h"
#include "interp.h"

namespace cellforge::csg {
namespace {

constexpr SourcePos kNoPos{~0u, 0, 0};  // a message that is already formatted

// AddressSanitizer unpoisons at most 64 MiB of stack when an exception leaves deep
// frames (and reports false errors beyond): under it the stack budget stays below
// (CMake defines CELLFORGE_ASAN in the sanitizer and fuzzer trees).
#ifdef CELLFORGE_ASAN
constexpr std::size_t kStackCap = 48u << 20;
#else
constexpr std::size_t kStackCap = ~std::size_t{0};
#endif

std::string folder_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

bool read_text(const std::string& path, std::string& out) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  out = s.str();
  return true;
}

}  // namespace

Interp::Interp(const EvalOptions& options, std::shared_ptr<Sources> sources)
    : options_(options), sources_(std::move(sources)) {}

Interp::~Interp() {
  // Closures hold their scope, and scopes may hold closures: break every cycle.
  for (const auto& w : closures_) {
    if (auto c = w.lock()) c->env.reset();
  }
}

void Interp::step(SourcePos pos) {
  if (++steps_ > options_.max_steps) {
    fail(pos, "the evaluation took more than " + std::to_string(options_.max_steps) +
                  " steps (an endless loop or recursion?)");
  }
}

void Interp::check_stack(SourcePos pos) {
  const char* here = static_cast<const char*>(__builtin_frame_address(0));
  if (stack_base_ != nullptr &&
      static_cast<std::size_t>(stack_base_ - here) > options_.max_stack_bytes) {
    fail(pos, "recursion too deep (more than " + std::to_string(options_.max_stack_bytes >> 20) +
                  " MiB of stack)");
  }
}

void Interp::fail(SourcePos pos, const std::string& message) const {
  throw EvalError{pos, message};
}

void Interp::warn(SourcePos pos, const std::string& message) {
  std::string text = sources_->format(pos, "warning: " + message);
  if (warnings_.size() < 10000) warnings_.push_back(text);
  if (options_.on_warning) options_.on_warning(text);
}

void Interp::echo(const std::string& line) {
  if (echoes_.size() < 1'000'000) echoes_.push_back(line);
  if (options_.on_echo) options_.on_echo(line);
}

const File& Interp::load(std::uint32_t source) {
  FileEntry& entry = files_[source];
  if (!entry.file) {
    auto r = parse(*sources_, source);
    if (!r) throw EvalError{kNoPos, r.error().message};
    entry.file = std::make_unique<File>(std::move(*r));
  }
  return *entry.file;
}

std::uint32_t Interp::resolve(const std::string& path, SourcePos from) {
  if (!options_.allow_files) fail(from, "reading '" + path + "' (files are turned off)");
  std::vector<std::string> candidates;
  if (!path.empty() && path[0] == '/') {
    candidates.push_back(path);
  } else {
    const auto it = source_paths_.find(from.file);
    candidates.push_back(folder_of(it != source_paths_.end() ? it->second : std::string()) + path);
    std::vector<std::string> dirs = options_.library_path;
    if (options_.use_default_library_path) {
      if (const char* env = std::getenv("OPENSCADPATH")) {
        std::string s = env;
        std::size_t start = 0;
        while (start <= s.size()) {
          const std::size_t colon = s.find(':', start);
          const std::string d =
              s.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
          if (!d.empty()) dirs.push_back(d);
          if (colon == std::string::npos) break;
          start = colon + 1;
        }
      }
      dirs.push_back("/usr/share/openscad/libraries");
    }
    for (const std::string& d : dirs) candidates.push_back(d + (d.back() == '/' ? "" : "/") + path);
  }
  for (const std::string& c : candidates) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(c, ec)) continue;
    const std::string key = std::filesystem::weakly_canonical(c, ec).string();
    if (auto it = by_path_.find(key); it != by_path_.end()) return it->second;
    std::string text;
    if (!read_text(c, text)) fail(from, "cannot read '" + c + "'");
    const std::uint32_t index = sources_->add(c, std::move(text));
    source_paths_[index] = c;
    by_path_[key] = index;
    return index;
  }
  fail(from, "cannot find '" + path +
                 "' (looked in the script's folder, OPENSCADPATH and "
                 "/usr/share/openscad/libraries)");
}

std::vector<const Stmt*> Interp::file_statements(const File& f, const EnvPtr& env, int depth) {
  if (depth > 64)
    fail(f.includes.empty() ? SourcePos{} : f.includes[0].pos,
         "include<> nested more than 64 deep (a cycle?)");
  std::vector<const Stmt*> out;
  std::size_t inc = 0;
  for (std::size_t i = 0; i <= f.statements.size(); ++i) {
    while (inc < f.includes.size() && f.includes[inc].before == i) {
      const Include& in = f.includes[inc++];
      const std::uint32_t src = resolve(in.path, in.pos);
      const File& g = load(src);
      if (in.use) {
        FileEntry& entry = files_[src];
        if (!entry.use_env) {
          entry.use_env = std::make_shared<Env>();
          const EnvPtr scope = entry.use_env;
          std::vector<const Stmt*> stmts = file_statements(g, scope, depth + 1);
          std::vector<const Stmt*> defs;
          for (const Stmt* s : stmts) {
            if (s->kind == StmtKind::kAssign || s->kind == StmtKind::kModule ||
                s->kind == StmtKind::kFunction)
              defs.push_back(s);
          }
          run_scope(defs, scope);
        }
        env->uses.push_back(entry.use_env);
      } else {
        std::vector<const Stmt*> sub = file_statements(g, env, depth + 1);
        out.insert(out.end(), sub.begin(), sub.end());
      }
    }
    if (i < f.statements.size()) out.push_back(f.statements[i].get());
  }
  return out;
}

EvalOutput Interp::run(std::uint32_t main_source) {
  auto top = std::make_shared<Env>();
  const File& f = load(main_source);
  std::vector<const Stmt*> stmts = file_statements(f, top, 0);
  std::vector<const Stmt*> defines;
  for (std::size_t i = 0; i < options_.defines.size(); ++i) {
    const auto& [name, value] = options_.defines[i];
    const std::uint32_t src = sources_->add("-D " + name, name + " = " + value + ";");
    const std::string key = "<-D " + std::to_string(i) + ">";
    source_paths_[src] = key;
    const File& d = load(src);
    if (d.statements.size() != 1 || d.statements[0]->kind != StmtKind::kAssign) {
      throw EvalError{kNoPos, "-D " + name + "=" + value + ": not name=expression"};
    }
    defines.push_back(d.statements[0].get());
  }
  std::vector<NodePtr> nodes = run_scope(stmts, top, &defines);
  EvalOutput out;
  out.root = root_override_ ? root_override_ : group(NodeKind::kGroup, std::move(nodes), {});
  out.echoes = std::move(echoes_);
  out.warnings = std::move(warnings_);
  out.sources = sources_;
  return out;
}

namespace {

struct Job {
  const EvalOptions* options;
  std::shared_ptr<Sources> sources;
  std::uint32_t main = 0;
  std::string main_path;
  std::optional<Result<EvalOutput>> result;
};

void run_job(Job& job) {
  Interp in(*job.options, job.sources);
  in.stack_base_ = static_cast<const char*>(__builtin_frame_address(0));
  in.source_paths_[job.main] = job.main_path;
  std::error_code ec;
  const std::string key = std::filesystem::weakly_canonical(job.main_path, ec).string();
  in.by_path_[key.empty() ? job.main_path : key] = job.main;
  try {
    job.result.emplace(in.run(job.main));
  } catch (const EvalError& e) {
    const bool parse_error = e.pos.file == kNoPos.file;
    job.result.emplace(Error{parse_error ? ErrorCode::kParse : ErrorCode::kInvalidInput,
                             parse_error ? e.message : job.sources->format(e.pos, e.message)});
  } catch (const std::bad_alloc&) {
    job.result.emplace(Error{ErrorCode::kInvalidInput, "the evaluation ran out of memory"});
  }
}

void* thread_main(void* arg) {
  run_job(*static_cast<Job*>(arg));
  return nullptr;
}

Result<EvalOutput> run_on_big_stack(Job& job) {
  EvalOptions capped = *job.options;
  capped.max_stack_bytes = std::min(capped.max_stack_bytes, kStackCap);
  job.options = &capped;
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, job.options->max_stack_bytes + (16u << 20));
  pthread_t thread;
  const int rc = pthread_create(&thread, &attr, thread_main, &job);
  pthread_attr_destroy(&attr);
  if (rc != 0) {
    // No thread: run here, with a stack budget this thread surely has.
    EvalOptions small = capped;
    small.max_stack_bytes = std::min<std::size_t>(small.max_stack_bytes, 2u << 20);
    job.options = &small;
    run_job(job);
  } else {
    pthread_join(thread, nullptr);
  }
  return std::move(*job.result);
}

}  // namespace

Result<EvalOutput> evaluate_text(const std::string& text, const std::string& name,
                                 const EvalOptions& options) {
  Job job;
  job.options = &options;
  job.sources = std::make_shared<Sources>();
  job.main = job.sources->add(name, text);
  job.main_path = name;
  return run_on_big_stack(job);
}

Result<EvalOutput> evaluate_file(const std::string& path, const EvalOptions& options) {
  std::string text;
  if (!read_text(path, text)) return Error{ErrorCode::kIo, "cannot read '" + path + "'"};
  return evaluate_text(text, path, options);
}

}  // namespace cellforge::csg
