#include "app/gui/main_window.h"

#include <QActionGroup>
#include <QApplication>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QHeaderView>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QTableWidget>
#include <QTextStream>

#include "app/gui/pinch_simulation.h"
#include "app/gui/scene_view.h"
#include "app/gui/study_panel.h"
#include "handlab/version.h"

namespace handlab::gui {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setWindowTitle(tr("handlab"));
  view_ = new SceneView(this);
  setCentralWidget(view_);
  build_menus();
  statusBar()->showMessage(tr("Drag to orbit, scroll to zoom"));
  resize(1100, 750);
}

void MainWindow::build_menus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(tr("Save View as &Image…"), this, &MainWindow::save_view_image);
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"), qApp, &QApplication::closeAllWindows);
  quit->setShortcut(QKeySequence::Quit);

  QMenu* study = menuBar()->addMenu(tr("&Study"));
  study->addAction(tr("&Open Study Database…"), this, &MainWindow::open_study);
  study->addSeparator();
  auto* cubes = new QActionGroup(this);
  for (const auto& [label, size] : {std::pair{tr("&Gross Manipulation (6 cm cube)"), 0.06},
                                    std::pair{tr("&Fine Manipulation (1 cm cube)"), 0.01}}) {
    QAction* action = study->addAction(label, this, [this, size = size] { set_cube_size(size); });
    action->setCheckable(true);
    action->setChecked(size == view_->layout().cube_size);
    cubes->addAction(action);
  }

  study->addSeparator();
  QAction* hands = study->addAction(tr("Show &Hands (simulated and tracked)"));
  hands->setCheckable(true);
  hands->setChecked(view_->show_hands());
  connect(hands, &QAction::toggled, view_, &SceneView::set_show_hands);

  QMenu* simulation = menuBar()->addMenu(tr("S&imulation"));
  simulation->addAction(tr("Run Scripted &Pinch-and-Lift"), this, [this] { start_pinch(); });
  simulation->addAction(tr("&Stop"), this, &MainWindow::stop_pinch);
  simulation->addSeparator();
  QAction* contacts = simulation->addAction(tr("Show &Contact Points"));
  contacts->setCheckable(true);
  connect(contacts, &QAction::toggled, this, &MainWindow::set_show_contacts);

  QMenu* analysis = menuBar()->addMenu(tr("&Analysis"));
  analysis->addAction(tr("Open Data &Table (CSV)…"), this, &MainWindow::open_csv_table);

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&About handlab"), this, &MainWindow::show_about);
  help->addAction(tr("About &Qt"), qApp, &QApplication::aboutQt);
}

PinchSimulation* MainWindow::start_pinch(double until) {
  stop_pinch();
  pinch_ = new PinchSimulation(view_->layout().cube_size, until, this);
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
  view_->set_frame(nullptr);
  statusBar()->showMessage(tr("Drag to orbit, scroll to zoom"));
}

void MainWindow::set_show_contacts(bool show) {
  show_contacts_ = show;
  show_pinch_state();
}

void MainWindow::show_pinch_state() {
  if (!pinch_ || !pinch_->has_state()) return;
  view_->set_frame(
      std::make_shared<const render::DrawList>(pinch_->draw(view_->layout(), show_contacts_)));
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
  if (!view_->grab_picture().save(path))
    QMessageBox::warning(this, tr("Save View"), tr("Could not write %1.").arg(path));
}

void MainWindow::set_cube_size(double metres) {
  task::SceneLayout layout = view_->layout();
  layout.cube_size = metres;
  view_->set_layout(layout);
}

void MainWindow::open_csv_table() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Data Table"), QString(),
                                                    tr("CSV files (*.csv);;All files (*)"));
  if (path.isEmpty()) return;
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly | QIODevice::Text)) {
    QMessageBox::warning(this, tr("Open Data Table"), tr("Could not read %1.").arg(path));
    return;
  }
  QTextStream in(&file);
  auto* table = new QTableWidget;
  int row = -1;
  while (!in.atEnd()) {
    const QStringList cells = in.readLine().split(',');
    if (row < 0) {
      table->setColumnCount(int(cells.size()));
      table->setHorizontalHeaderLabels(cells);
    } else {
      table->insertRow(row);
      for (int c = 0; c < cells.size() && c < table->columnCount(); ++c)
        table->setItem(row, c, new QTableWidgetItem(cells[c]));
    }
    ++row;
  }
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  auto* dock = new QDockWidget(QFileInfo(path).fileName(), this);
  dock->setWidget(table);
  dock->setAttribute(Qt::WA_DeleteOnClose);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  statusBar()->showMessage(tr("%1: %2 rows").arg(QFileInfo(path).fileName()).arg(row), 5000);
}

void MainWindow::open_study() {
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open Study Database"), QString(),
                                   tr("Study databases (*.db *.sqlite);;All files (*)"));
  if (path.isEmpty()) return;
  const QString error = show_study(path);
  if (!error.isEmpty()) QMessageBox::warning(this, tr("Open Study Database"), error);
}

QString MainWindow::show_study(const QString& path) {
  auto* panel = new StudyPanel;
  const QString error = panel->open_database(path);
  if (!error.isEmpty()) {
    delete panel;
    return error;
  }
  auto* dock = new QDockWidget(tr("Study: %1").arg(QFileInfo(path).fileName()), this);
  dock->setObjectName("study");
  dock->setWidget(panel);
  dock->setAttribute(Qt::WA_DeleteOnClose);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  statusBar()->showMessage(tr("Opened %1").arg(QFileInfo(path).fileName()), 5000);
  return {};
}

void MainWindow::show_about() {
  QMessageBox::about(this, tr("About handlab"),
                     tr("<b>handlab %1</b><p>Runs and analyses user studies of fine virtual "
                        "manipulation with tracked hands driving a simulated soft hand.</p>")
                         .arg(HANDLAB_VERSION));
}

}  // namespace handlab::gui
