// For the filter modules' tests (as IO/Testing is for the IO modules'): the
// error messages an algorithm reports while it runs, its own and its
// executive's, to check that a failure is "one clear error".
#ifndef LVDIF_FILTERS_ALGORITHM_ERRORS_TEST_UTIL_H
#define LVDIF_FILTERS_ALGORITHM_ERRORS_TEST_UTIL_H

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"

#include <string>
#include <vector>

/// Records every ErrorEvent of `algorithm` and of its executive from now on.
class AlgorithmErrors
{
public:
  explicit AlgorithmErrors(vtkAlgorithm* algorithm)
  {
    vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on
    this->Callback->SetClientData(&this->Messages);
    this->Callback->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      if (client) // null once the recorder is gone (the algorithm may outlive it)
        static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call));
    });
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Callback);
  }
  ~AlgorithmErrors() { this->Callback->SetClientData(nullptr); }
  AlgorithmErrors(const AlgorithmErrors&) = delete;
  AlgorithmErrors& operator=(const AlgorithmErrors&) = delete;
  const std::vector<std::string>& messages() const { return this->Messages; }
  /// The first and the last message, for a failed assertion's text.
  std::string summary() const
  {
    return this->Messages.empty() ? "" : this->Messages.front() + " / " + this->Messages.back();
  }

private:
  std::vector<std::string> Messages;
  vtkNew<vtkCallbackCommand> Callback;
};

#endif
