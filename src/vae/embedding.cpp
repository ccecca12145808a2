#include "vae/embedding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "util/csv_log.h"

namespace vaegail::vae {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string header(size_t latent) {
  std::string h = "episode,expert_id,context,achieved_speed,held_out";
  for (size_t j = 0; j < latent; ++j) h += ",mu_" + std::to_string(j);
  for (size_t j = 0; j < latent; ++j) h += ",sigma_" + std::to_string(j);
  return h;
}

double squared_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t j = 0; j < a.size(); ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return s;
}

}  // namespace

std::string embedding_csv(const std::vector<EmbeddingRow>& rows) {
  const size_t latent = rows.empty() ? 0 : rows[0].mu.size();
  std::string out = header(latent) + "\n";
  for (const auto& r : rows) {
    if (r.mu.size() != latent || r.sigma.size() != latent)
      throw std::invalid_argument("embedding_csv: rows differ in latent size");
    if (r.expert_id.find_first_of(",\n") != std::string::npos)
      throw std::invalid_argument("embedding_csv: expert id '" + r.expert_id + "' holds a comma or newline");
    out += std::to_string(r.episode) + "," + r.expert_id + "," + number(r.context) + "," +
           number(r.achieved_speed) + "," + (r.held_out ? "1" : "0");
    for (double v : r.mu) out += "," + number(v);
    for (double v : r.sigma) out += "," + number(v);
    out += "\n";
  }
  return out;
}

std::vector<EmbeddingRow> parse_embedding_csv(const std::string& text, const std::string& where) {
  std::stringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw std::invalid_argument(where + ": empty file");
  const auto columns = split_csv_line(line);
  if (columns.size() < 5 || (columns.size() - 5) % 2 != 0 ||
      line != header((columns.size() - 5) / 2))
    throw std::invalid_argument(where + ": line 1: not an embedding header (" + header(1) + "...)");
  const size_t latent = (columns.size() - 5) / 2;
  std::vector<EmbeddingRow> rows;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const auto cells = split_csv_line(line);
    const std::string at = where + ": line " + std::to_string(n) + ": ";
    if (cells.size() != columns.size())
      throw std::invalid_argument(at + std::to_string(cells.size()) + " cells, expected " +
                                  std::to_string(columns.size()));
    EmbeddingRow r;
    try {
      size_t used = 0;
      auto num = [&](const std::string& s) {
        const double v = std::stod(s, &used);
        if (used != s.size()) throw std::invalid_argument(s);
        return v;
      };
      r.episode = static_cast<int>(num(cells[0]));
      r.expert_id = cells[1];
      r.context = num(cells[2]);
      r.achieved_speed = num(cells[3]);
      r.held_out = num(cells[4]) != 0.0;
      for (size_t j = 0; j < latent; ++j) r.mu.push_back(num(cells[5 + j]));
      for (size_t j = 0; j < latent; ++j) r.sigma.push_back(num(cells[5 + latent + j]));
    } catch (const std::exception&) {
      throw std::invalid_argument(at + "a cell is not a number");
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

KnnResult knn_classify(const std::vector<EmbeddingRow>& rows, int k) {
  if (k < 1) throw std::invalid_argument("knn: k must be >= 1");
  std::vector<const EmbeddingRow*> train, queries;
  for (const auto& r : rows) (r.held_out ? queries : train).push_back(&r);
  if (train.empty()) throw std::invalid_argument("knn: no training rows (held_out = 0)");
  if (queries.empty()) throw std::invalid_argument("knn: no held-out rows (held_out = 1) to classify");
  KnnResult result;
  result.k = std::min<int>(k, static_cast<int>(train.size()));
  for (const auto* q : queries) {
    std::vector<std::pair<double, const EmbeddingRow*>> by_distance;
    for (const auto* t : train) by_distance.push_back({squared_distance(q->mu, t->mu), t});
    std::partial_sort(by_distance.begin(), by_distance.begin() + result.k, by_distance.end(),
                      [](const auto& a, const auto& b) { return a.first < b.first; });
    std::map<double, int> votes;
    for (int i = 0; i < result.k; ++i) ++votes[by_distance[i].second->context];
    int best_votes = 0;
    for (const auto& [context, n] : votes) best_votes = std::max(best_votes, n);
    double predicted = 0;
    for (int i = 0; i < result.k; ++i) {  // nearest first: the first tied winner met wins
      const double c = by_distance[i].second->context;
      if (votes[c] == best_votes) {
        predicted = c;
        break;
      }
    }
    const bool hit = predicted == q->context;
    result.total += 1;
    result.correct += hit;
    auto& target = result.per_target[q->context];
    target.first += hit;
    target.second += 1;
  }
  return result;
}

std::string format_knn(const KnnResult& r) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "k-NN (k = %d) on held-out embeddings: %d / %d = %.1f%%  (bar: >= 90%%)\n",
                r.k, r.correct, r.total, 100.0 * r.accuracy());
  std::string out = buf;
  for (const auto& [context, ct] : r.per_target) {
    std::snprintf(buf, sizeof buf, "  target %+g: %d / %d = %.1f%%\n", context, ct.first, ct.second,
                  100.0 * ct.first / ct.second);
    out += buf;
  }
  return out;
}

}  // namespace vaegail::vae
