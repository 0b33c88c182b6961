from enum import StrEnum

class ValidationNamed(StrEnum):
    VAL_SET = "val_set"

    def __str__(self) -> str:
        return str(self.value)
