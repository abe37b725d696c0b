#include "app/gui/live_measurement.h"

#include <cstdio>
#include <sstream>

#include <QTimer>

#include "analysis/stats/descriptives.h"
#include "app/gui/session_page.h"
#include "app/gui/session_worker.h"
#include "core/util/json_writer.h"
#include "core/util/output_file.h"

namespace handlab::gui {
namespace {

constexpr int kWarmUpMs = 3000;  // the soft hand's flesh is built as the first trial starts

}  // namespace

LiveMeasurement::LiveMeasurement(SessionPage* page, double seconds, QString json_path,
                                 QObject* parent)
    : QObject(parent), page_(page), seconds_(seconds), json_path_(std::move(json_path)) {
  connect(page_, &SessionPage::session_started, this, [this] {
    connect(page_->worker(), &SessionWorker::trial_started, this, [this] {
      if (started_) return;
      started_ = true;
      QTimer::singleShot(kWarmUpMs, this, &LiveMeasurement::begin);
    });
  });
  connect(page_, &SessionPage::session_ended, this, [this] {
    if (!taken_) {
      figures_.clear();
      emit done(false);
      return;
    }
    try {
      util::write_output_bytes(json_path_.toStdString(), figures_.toStdString());
    } catch (const util::OutputError& e) {
      std::fprintf(stderr, "handlab: %s\n", e.what());
      emit done(false);
      return;
    }
    emit done(true);
  });
}

void LiveMeasurement::begin() {
  page_->reset_display_stats();
  QTimer::singleShot(int(seconds_ * 1000), this, &LiveMeasurement::finish);
}

void LiveMeasurement::finish() {
  SessionPage::DisplayStats s = page_->display_stats();
  // Quantiles of arrival to screen, and of its part until the simulated state was there.
  auto summary = [](util::JsonWriter& json, const char* name, std::vector<double> ms) {
    auto q = [&](double p) { return stats::timing_quantile(ms, p); };
    json.key(name)
        .begin_object()
        .field("n", ms.size())
        .field("median", q(0.5))
        .field("p99", q(0.99))
        .field("max", q(1.0))
        .end_object();
  };
  std::ostringstream text;
  util::JsonWriter json(text);
  json.begin_object()
      .field("seconds", s.seconds)
      .field("frames_used", (long long)s.frames_used)
      .field("frames_dropped", (long long)s.frames_superseded)
      .field("frames_shown", s.latency_ms.size())
      .field("pictures", (long long)s.pictures)
      .field("display_rate_hz", s.seconds > 0 ? double(s.pictures - 1) / s.seconds : 0.0);
  summary(json, "latency_ms", s.latency_ms);
  summary(json, "pipeline_ms", s.pipeline_ms);
  json.end_object();
  text << '\n';
  figures_ = QString::fromStdString(text.str());
  taken_ = true;
  page_->stop_session();
}

}  // namespace handlab::gui
