#include "app/gui/main_window.h"

#include "app/report/report_files.h"

#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QGuiApplication>
#include <QHeaderView>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QScopeGuard>
#include <QScreen>
#include <QSettings>
#include <QStatusBar>
#include <QTabWidget>
#include <QTableView>
#include <QVBoxLayout>

#include "app/gui/analysis_page.h"
#include "app/gui/participant_window.h"
#include "app/gui/participants_page.h"
#include "app/gui/pinch_simulation.h"
#include "app/gui/scene_view.h"
#include "app/gui/session_page.h"
#include "app/gui/session_worker.h"
#include "app/gui/study_home.h"
#include "app/gui/text_table_model.h"
#include "app/report/figure_file.h"
#include "app/report/report_files.h"
#include "core/store/study_store.h"
#include "core/util/build_info.h"
#include "core/util/csv.h"
#include "core/util/data_files.h"
#include "core/util/output_file.h"
#include "studies/export/study_export.h"
#include "studies/session/enrolment.h"
#include "studies/session/session_runner.h"

namespace handlab::gui {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  tabs_ = new QTabWidget;
  home_ = new StudyHome;
  participants_ = new ParticipantsPage;
  session_ = new SessionPage;
  analysis_ = new AnalysisPage;
  tabs_->addTab(home_, tr("&Study"));
  tabs_->addTab(participants_, tr("&Participants"));
  tabs_->addTab(session_, tr("S&ession"));
  tabs_->addTab(analysis_, tr("&Analysis"));
  setCentralWidget(tabs_);

  connect(home_, &StudyHome::new_study_requested, this, &MainWindow::new_study_dialog);
  connect(home_, &StudyHome::open_study_requested, this, &MainWindow::open_study_dialog);
  connect(home_, &StudyHome::open_recent_requested, this, [this](const QString& path) {
    const QString error = open_study(path);
    if (!error.isEmpty()) show_error(tr("Open Study"), error);
  });
  connect(home_, &StudyHome::resume_requested, this, [this](const QString& id) {
    participants_->refresh(id);  // the session page follows the selection
    tabs_->setCurrentWidget(session_);
  });
  connect(participants_, &ParticipantsPage::participants_changed, this,
          [this](const QStringList& ids, const QString& selected) {
            session_->set_participants(ids, selected);
          });
  connect(participants_, &ParticipantsPage::replay_requested, this,
          [this](const QString& id, int position) {
            const QString error = session_->replay_trial(id, position);
            if (!error.isEmpty()) {
              statusBar()->showMessage(tr("Replay: %1").arg(error), 8000);
              return;
            }
            tabs_->setCurrentWidget(session_);
          });
  connect(session_, &SessionPage::study_changed, this, &MainWindow::refresh_study);
  connect(session_, &SessionPage::session_started, this,
          [this] { participants_->set_in_session(session_->participant_box()->currentText()); });
  connect(session_, &SessionPage::session_ended, this, [this](const QString& summary) {
    participants_->set_in_session({});
    refresh_study();
    statusBar()->showMessage(summary, 10000);
  });

  build_menus();
  setWindowTitle(tr("handlab"));
  QSettings settings;
  home_->set_recent(settings.value("recent").toStringList());
  statusBar()->showMessage(tr("Create or open a study to begin"));
  resize(1280, 820);
}

MainWindow::~MainWindow() {
  stop_pinch();
}

void MainWindow::build_menus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(tr("&New Study…"), QKeySequence::New, this, &MainWindow::new_study_dialog);
  file->addAction(tr("&Open Study…"), QKeySequence::Open, this, &MainWindow::open_study_dialog);
  recent_menu_ = file->addMenu(tr("Open &Recent"));
  connect(recent_menu_, &QMenu::aboutToShow, this, [this] {
    recent_menu_->clear();
    for (const QString& path : QSettings().value("recent").toStringList())
      recent_menu_->addAction(path, this, [this, path] {
        const QString error = open_study(path);
        if (!error.isEmpty()) show_error(tr("Open Study"), error);
      });
  });
  file->addSeparator();
  file->addAction(tr("Export &Trials (trials.csv)…"), this,
                  [this] { export_dialog(Table::kTrials); });
  file->addAction(tr("Export &Questionnaire (questionnaire.csv)…"), this,
                  [this] { export_dialog(Table::kQuestionnaire); });
  file->addAction(tr("Export &Frames (frames.csv)…"), this,
                  [this] { export_dialog(Table::kFrames); });
  file->addAction(tr("Export &Report (HTML and PDF)…"), this, &MainWindow::export_report_dialog);
  file->addAction(tr("Open &Data Table (CSV)…"), this, &MainWindow::open_data_table_dialog);
  file->addAction(tr("Save View as &Image…"), this, &MainWindow::save_view_image);
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"), qApp, &QApplication::closeAllWindows);
  quit->setShortcut(QKeySequence::Quit);

  QMenu* session = menuBar()->addMenu(tr("S&ession"));
  session->addAction(tr("&Start or Resume"), QKeySequence(Qt::Key_F5), this, [this] {
    tabs_->setCurrentWidget(session_);
    const QString error = session_->start_session();
    if (!error.isEmpty()) statusBar()->showMessage(error, 8000);
  });
  session->addAction(tr("&Pause After This Trial"), QKeySequence(Qt::Key_F6), session_,
                     &SessionPage::toggle_pause);
  session->addAction(tr("S&top"), QKeySequence(Qt::Key_F8), session_, &SessionPage::stop_session);
  session->addSeparator();
  session->addAction(tr("&Add Participant…"), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_A), this,
                     [this] {
                       tabs_->setCurrentWidget(participants_);
                       participants_->add_participant();
                     });

  QMenu* view = menuBar()->addMenu(tr("&View"));
  QMenu* screens = view->addMenu(tr("&Participant Window"));
  connect(screens, &QMenu::aboutToShow, this, [this, screens] {
    screens->clear();
    screens->addAction(tr("In a Window"), QKeySequence(Qt::CTRL | Qt::Key_P), this,
                       [this] { show_participant_window(-1); });
    const auto list = QGuiApplication::screens();
    for (int k = 0; k < list.size(); ++k)
      screens->addAction(tr("Full Screen on %1").arg(list[k]->name()), this,
                         [this, k] { show_participant_window(k); });
  });
  QAction* hands = view->addAction(tr("Show &Hands in the Idle Scene"));
  hands->setCheckable(true);
  hands->setChecked(scene_view()->show_hands());
  connect(hands, &QAction::toggled, scene_view(), &SceneView::set_show_hands);
  auto* cubes = new QActionGroup(this);
  for (const auto& [label, size] : {std::pair{tr("&Gross Manipulation (6 cm cube)"), 0.06},
                                    std::pair{tr("&Fine Manipulation (1 cm cube)"), 0.01}}) {
    QAction* action = view->addAction(label, this, [this, size = size] { set_cube_size(size); });
    action->setCheckable(true);
    action->setChecked(size == scene_view()->layout().cube_size);
    cubes->addAction(action);
  }

  QMenu* simulation = menuBar()->addMenu(tr("S&imulation"));
  simulation->addAction(tr("Run Scripted &Pinch-and-Lift"), this, [this] { start_pinch(); });
  simulation->addAction(tr("&Stop"), this, &MainWindow::stop_pinch);
  simulation->addSeparator();
  QAction* contacts = simulation->addAction(tr("Show &Contact Points"));
  contacts->setCheckable(true);
  connect(contacts, &QAction::toggled, this, &MainWindow::set_show_contacts);

  QMenu* analysis = menuBar()->addMenu(tr("&Analysis"));
  analysis->addAction(tr("&Run Analysis"), this, [this] {
    tabs_->setCurrentWidget(analysis_);
    analysis_->run();
  });
  analysis->addAction(tr("Open Data &Table (CSV)…"), this, &MainWindow::open_data_table_dialog);

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&About handlab"), this, &MainWindow::show_about);
  help->addAction(tr("About &Qt"), qApp, &QApplication::aboutQt);
}

void MainWindow::show_error(const QString& title, const QString& error) {
  QMessageBox::warning(this, title, error);
}

QString MainWindow::open_study(const QString& path) {
  if (session_->session_running())
    return tr("Stop the running session before opening another study.");
  auto show = [this](const OpenStudy& study) {
    home_->set_study(study);
    participants_->set_study(study);
    session_->set_study(study);
    analysis_->set_study(study.path);  // its analysis runs on a thread of its own
  };
  try {
    OpenStudy study{QFileInfo(path).absoluteFilePath(),
                    std::make_shared<store::StudyStore>(path.toStdString())};
    study.store->study();
    show(study);
    study_ = std::move(study);
  } catch (const std::exception& e) {
    try {  // every page back on the study the window had open
      show(study_);
    } catch (const std::exception&) {
      show(OpenStudy{});
      study_ = {};
    }
    return QString::fromStdString(e.what());
  }
  remember_recent(study_.path);
  setWindowTitle(tr("%1 — handlab").arg(QFileInfo(study_.path).fileName()));
  setWindowFilePath(study_.path);
  statusBar()->showMessage(tr("Opened %1").arg(study_.path), 5000);
  return {};
}

QString MainWindow::create_study(const QString& protocol, const QString& database) {
  try {
    const studies::Protocol p = studies::read_protocol(protocol.toStdString());
    store::StudyStore::create(database.toStdString(), studies::study_definition(p));
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
  return open_study(database);
}

QString MainWindow::show_study(const QString& path) {
  const QString error = open_study(path);
  if (error.isEmpty()) tabs_->setCurrentWidget(participants_);
  return error;
}

void MainWindow::refresh_study() {
  if (!study_.is_open()) return;
  const QString own =
      session_->session_running() ? session_->participant_box()->currentText() : QString();
  // A view that cannot be read now says so; the session stores its trials on its own
  // connection whatever happens here.
  try {
    home_->set_study(study_, own);
    participants_->refresh();
  } catch (const std::exception& e) {
    statusBar()->showMessage(
        tr("The study's views could not be refreshed: %1").arg(QString::fromStdString(e.what())),
        15000);
  }
}

void MainWindow::remember_recent(const QString& path) {
  QSettings settings;
  QStringList recent = settings.value("recent").toStringList();
  recent.removeAll(path);
  recent.prepend(path);
  while (recent.size() > 8) recent.removeLast();
  settings.setValue("recent", recent);
  home_->set_recent(recent);
}

void MainWindow::new_study_dialog() {
  // Installed, the package's protocols are where to look first.
  const QString installed =
      QString::fromStdString(util::installed_data_directory()) + QStringLiteral("/studies");
  const QString protocol = QFileDialog::getOpenFileName(
      this, tr("New Study: choose the protocol"), QDir(installed).exists() ? installed : QString(),
      tr("Study protocols (*.json)"));
  if (protocol.isEmpty()) return;
  studies::Protocol p;
  try {
    p = studies::read_protocol(protocol.toStdString());
  } catch (const std::exception& e) {
    show_error(tr("New Study"), QString::fromStdString(e.what()));
    return;
  }
  // The protocol in a few lines, checked before anything is created.
  QDialog summary(this);
  summary.setWindowTitle(tr("New Study from %1").arg(QFileInfo(protocol).fileName()));
  auto* layout = new QVBoxLayout(&summary);
  std::vector<TextRow> rows;
  for (const auto& [label, value] : studies::protocol_summary(p))
    rows.push_back({{QString::fromStdString(label), QString::fromStdString(value)}, {}, {}});
  auto* table = new QTableView;
  table->setObjectName("protocol_summary");
  table->setModel(new TextTableModel({tr("Item"), tr("Value")}, table));
  static_cast<TextTableModel*>(table->model())->set_rows(std::move(rows));
  table->horizontalHeader()->hide();
  table->verticalHeader()->hide();
  table->horizontalHeader()->setStretchLastSection(true);
  table->resizeColumnToContents(0);
  layout->addWidget(table);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  buttons->button(QDialogButtonBox::Ok)->setText(tr("Create Study File…"));
  connect(buttons, &QDialogButtonBox::accepted, &summary, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, &summary, &QDialog::reject);
  layout->addWidget(buttons);
  summary.resize(760, 560);
  if (summary.exec() != QDialog::Accepted) return;
  const QString database = QFileDialog::getSaveFileName(this, tr("New Study: the study file"),
                                                        QString::fromStdString(p.name) + ".db",
                                                        tr("Study databases (*.db)"));
  if (database.isEmpty()) return;
  const QString error = create_study(protocol, database);
  if (!error.isEmpty()) show_error(tr("New Study"), error);
}

void MainWindow::open_study_dialog() {
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open Study"), QString(), tr("Study databases (*.db *.sqlite);;All files (*)"));
  if (path.isEmpty()) return;
  const QString error = open_study(path);
  if (!error.isEmpty()) show_error(tr("Open Study"), error);
}

QString MainWindow::export_table(const QString& path, Table table) {
  if (!study_.is_open()) return tr("No study is open.");
  // The frame log of a whole study is millions of rows: seconds, not a moment.
  const bool long_job = table == Table::kFrames;
  if (long_job) {
    QApplication::setOverrideCursor(Qt::WaitCursor);
    statusBar()->showMessage(tr("Writing %1…").arg(path));
    QApplication::processEvents();
  }
  const auto restore = qScopeGuard([long_job] {
    if (long_job) QApplication::restoreOverrideCursor();
  });
  try {
    store::StudyStore& store = *study_.store;
    util::write_output(path.toStdString(), [&](std::ostream& out) {
      switch (table) {
        case Table::kTrials:
          studies::write_trials_csv(store, out);
          break;
        case Table::kQuestionnaire:
          studies::write_questionnaire_csv(store, out);
          break;
        case Table::kFrames:
          studies::write_frames_csv(store, out);
          break;
      }
    });
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
  statusBar()->showMessage(tr("Wrote %1").arg(path), 5000);
  return {};
}

void MainWindow::export_dialog(Table table) {
  const QString title = table == Table::kTrials          ? tr("Export Trials")
                        : table == Table::kQuestionnaire ? tr("Export Questionnaire")
                                                         : tr("Export Frames");
  const QString name = table == Table::kTrials          ? "trials.csv"
                       : table == Table::kQuestionnaire ? "questionnaire.csv"
                                                        : "frames.csv";
  const QString path = QFileDialog::getSaveFileName(this, title, name, tr("CSV files (*.csv)"));
  if (path.isEmpty()) return;
  const QString error = export_table(path, table);
  if (!error.isEmpty()) show_error(tr("Export"), error);
}

QString MainWindow::export_report(const QString& folder) {
  if (!study_.is_open()) return tr("No study is open.");
  QApplication::setOverrideCursor(Qt::WaitCursor);
  statusBar()->showMessage(tr("Writing the report…"));
  report::ReportFiles files;
  QString error;
  try {
    report::ReportRequest request;
    request.database = study_.path.toStdString();
    request.folder = folder.toStdString();
    files = report::write_report(request);
  } catch (const std::exception& e) {
    error = QString::fromStdString(e.what());
  }
  QApplication::restoreOverrideCursor();
  if (!error.isEmpty()) {
    statusBar()->clearMessage();
    return error;
  }
  statusBar()->showMessage(tr("Wrote %1 and %2 (%3 pages)")
                               .arg(QString::fromStdString(files.html))
                               .arg(QString::fromStdString(files.pdf))
                               .arg(files.pdf_pages),
                           8000);
  return {};
}

void MainWindow::export_report_dialog() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Export Report into Folder"));
  if (folder.isEmpty()) return;
  const QString error = export_report(folder);
  if (!error.isEmpty()) show_error(tr("Export Report"), error);
}

QString MainWindow::open_data_table(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) return tr("Could not read %1.").arg(path);
  const QByteArray bytes = file.readAll();
  std::vector<std::vector<std::string>> rows;
  try {
    rows = util::parse_csv(std::string_view(bytes.constData(), std::size_t(bytes.size())));
  } catch (const std::exception& e) {
    return tr("%1: %2").arg(path, QString::fromStdString(e.what()));
  }
  auto* model = new TextTableModel;
  if (!rows.empty()) {
    QStringList header;
    for (const auto& h : rows.front()) header << QString::fromStdString(h);
    std::vector<TextRow> cells;
    for (std::size_t r = 1; r < rows.size(); ++r) {
      TextRow row;
      for (std::size_t c = 0; c < rows[r].size() && c < rows.front().size(); ++c)
        row.cells << QString::fromStdString(rows[r][c]);
      cells.push_back(std::move(row));
    }
    model->set_headers(header);
    model->set_rows(std::move(cells));
  }
  auto* table = new QTableView;
  table->setObjectName("data_table");
  model->setParent(table);
  table->setModel(model);
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  auto* dock = new QDockWidget(QFileInfo(path).fileName(), this);
  dock->setObjectName("data_table_dock");
  dock->setWidget(table);
  dock->setAttribute(Qt::WA_DeleteOnClose);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  statusBar()->showMessage(
      tr("%1: %2 rows").arg(QFileInfo(path).fileName()).arg(rows.empty() ? 0 : rows.size() - 1),
      5000);
  return {};
}

void MainWindow::open_data_table_dialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Data Table"), QString(),
                                                    tr("CSV files (*.csv);;All files (*)"));
  if (path.isEmpty()) return;
  const QString error = open_data_table(path);
  if (!error.isEmpty()) show_error(tr("Open Data Table"), error);
}

ParticipantWindow* MainWindow::show_participant_window(int screen) {
  if (!participant_window_) {
    participant_window_ = new ParticipantWindow(this);
    session_->set_participant_window(participant_window_);
  }
  participant_window_->show_on_screen(screen);
  return participant_window_;
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (session_->session_running()) {
    const auto answer = QMessageBox::question(
        this, tr("Quit handlab"),
        tr("A session is running. Quit anyway? The trial under way is kept as aborted and runs "
           "again when the session resumes; every finished trial is stored."));
    if (answer != QMessageBox::Yes) {
      event->ignore();
      return;
    }
  }
  if (participant_window_) {
    participant_window_->end_questionnaire();  // the app ends: not asked again elsewhere
    participant_window_->close();
  }
  event->accept();
}

SceneView* MainWindow::scene_view() const {
  return session_->view();
}

PinchSimulation* MainWindow::start_pinch(double until) {
  stop_pinch();
  pinch_ = new PinchSimulation(scene_view()->layout().cube_size, until, this);
  connect(pinch_, &PinchSimulation::advanced, this, &MainWindow::show_pinch_state);
  connect(pinch_, &PinchSimulation::done, this, [this, sim = pinch_] {
    if (sim != pinch_) return;
    show_pinch_state();
    const QString error = sim->error();
    statusBar()->showMessage(
        error.isEmpty()
            ? tr("Simulated pinch-and-lift: finished at %1 s").arg(sim->progress().time, 0, 'f', 2)
            : tr("Simulation stopped: %1").arg(error));
  });
  statusBar()->showMessage(tr("Building the soft hand…"));
  return pinch_;
}

void MainWindow::stop_pinch() {
  if (!pinch_) return;
  delete pinch_;  // stops and joins its worker
  pinch_ = nullptr;
  scene_view()->set_frame(nullptr);
}

void MainWindow::set_show_contacts(bool show) {
  show_contacts_ = show;
  show_pinch_state();
}

void MainWindow::show_pinch_state() {
  if (!pinch_ || !pinch_->has_state()) return;
  scene_view()->set_frame(std::make_shared<const render::DrawList>(
      pinch_->draw(scene_view()->layout(), show_contacts_)));
  if (pinch_->finished()) return;
  const PinchSimulation::Progress p = pinch_->progress();
  statusBar()->showMessage(tr("Simulated pinch-and-lift: t = %1 s, last step %2 ms, %3 contact "
                              "points")
                               .arg(p.time, 0, 'f', 2)
                               .arg(p.step_ms, 0, 'f', 1)
                               .arg(p.contacts));
}

void MainWindow::save_view_image() {
  const QString path =
      QFileDialog::getSaveFileName(this, tr("Save View"), "view.png", tr("PNG images (*.png)"));
  if (path.isEmpty()) return;
  try {
    report::write_png_file(path.toStdString(), scene_view()->grab_picture());
  } catch (const std::exception& e) {
    QMessageBox::warning(this, tr("Save View"), QString::fromStdString(e.what()));
  }
}

void MainWindow::set_cube_size(double metres) {
  task::SceneLayout layout = scene_view()->layout();
  layout.cube_size = metres;
  scene_view()->set_layout(layout);
}

void MainWindow::show_about() {
  QMessageBox::about(this, tr("About handlab"),
                     tr("<b>handlab %1</b><p>Runs and analyses user studies of fine virtual "
                        "manipulation with tracked hands driving a simulated soft hand.</p>")
                         .arg(QString::fromStdString(util::version_line())));
}

}  // namespace handlab::gui
